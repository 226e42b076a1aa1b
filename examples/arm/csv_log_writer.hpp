// Buffered writer of the project's CSV log (docs log-format.md, version 1). The loop pushes
// samples into a preallocated single-producer/single-consumer ring; a background thread formats
// and writes them, so the real-time path never touches the file.
#pragma once

#include <atomic>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "arm/cycle_sample.hpp"

namespace tpf::arm {

struct LogMetadata {
  std::string robot = "arm4";
  double rate_hz = 400.0;
  std::string note;  ///< e.g. "recorded on the arm by tpf_arm_loop"
};

class CsvLogWriter {
 public:
  /// Opens `path` and writes "# tpf-log: 1", the metadata and the header
  /// t,q1..qN,dq1..dqN,i1..iN,p1..pM. Throws tpf::Error naming the path.
  CsvLogWriter(const std::string& path, std::size_t joints, std::size_t pads,
               const LogMetadata& metadata, std::size_t capacity = 8192);
  ~CsvLogWriter();
  CsvLogWriter(const CsvLogWriter&) = delete;
  CsvLogWriter& operator=(const CsvLogWriter&) = delete;

  /// Real-time side: copies the sample into the ring; false (and counted) when full.
  bool push(const CycleSample& sample) noexcept;
  /// Writes everything pushed so far and closes the file (also done by the destructor).
  void close();

  std::uint64_t rows_written() const noexcept { return written_.load(); }
  std::uint64_t rows_dropped() const noexcept { return dropped_.load(); }

 private:
  void drain();
  void write_row(const CycleSample& s);

  std::FILE* file_ = nullptr;
  std::size_t joints_, pads_;
  std::vector<CycleSample> ring_;
  std::atomic<std::uint64_t> head_{0}, tail_{0};  ///< head: next push, tail: next write
  std::atomic<std::uint64_t> written_{0}, dropped_{0};
  std::atomic<bool> running_{true};
  std::thread thread_;
};

}  // namespace tpf::arm
