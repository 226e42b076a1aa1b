// The loop's log, in tpf's one log format (docs/log-format.md) through tpf's one writer
// (offline::LogWriter, so the tools read it back as they read any log). The real-time thread pushes
// CycleSamples into a preallocated single-producer/single-consumer ring; a background thread turns
// them into rows and writes them, so the real-time path never touches the file.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include "arm/cycle_sample.hpp"
#include "offline/log/log_metadata.hpp"
#include "offline/log/log_writer.hpp"

namespace tpf::arm {

/// What a row holds: t, q1..qN, dq1..dqN, i1..iN, p1..pM and, with `estimates`, the estimator's
/// answer est_tau_ext1..N, est_contact, est_pad, est_fx, est_fy, est_fz, est_status.
struct RecordedColumns {
  std::size_t joints = 0;
  std::size_t pads = 0;
  bool estimates = false;
};

/// The header of a recorded log.
std::vector<std::string> recorded_column_names(const RecordedColumns& columns);

class LogRecorder {
 public:
  /// Opens the log (a temporary beside `path`, renamed into place by close(); a path ending in
  /// ".gz" is compressed) with `metadata` ("robot", "rate_hz", "note" …). Throws tpf::Error naming
  /// the path.
  LogRecorder(const std::string& path, RecordedColumns columns, offline::LogMetadata metadata,
              std::size_t capacity = 8192);
  ~LogRecorder();
  LogRecorder(const LogRecorder&) = delete;
  LogRecorder& operator=(const LogRecorder&) = delete;

  /// Real-time side: copies the sample into the ring; false (and counted) when full.
  bool push(const CycleSample& sample) noexcept;
  /// Writes everything pushed so far and puts the log in place (also done by the destructor).
  /// Throws tpf::Error when the writer failed (the rows it refused are counted).
  void close();

  std::uint64_t rows_written() const noexcept { return written_.load(); }
  std::uint64_t rows_dropped() const noexcept { return dropped_.load(); }
  /// Rows the writer refused (an I/O error): recording stops at the first, its message kept.
  std::uint64_t rows_failed() const noexcept { return failed_.load(); }

 private:
  void drain();
  void write(const CycleSample& s);
  void fill_row(const CycleSample& s);

  offline::LogWriter writer_;
  RecordedColumns columns_;
  std::vector<double> row_;
  std::vector<CycleSample> ring_;
  std::atomic<std::uint64_t> head_{0}, tail_{0};  ///< head: next push, tail: next write
  std::atomic<std::uint64_t> written_{0}, dropped_{0}, failed_{0};
  std::string error_;  ///< the writer's first error (written by the background thread)
  std::atomic<bool> running_{true};
  std::thread thread_;
};

}  // namespace tpf::arm
