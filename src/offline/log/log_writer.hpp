// Writing tpf logs: streaming (simulators, recorders) and whole-log (tools).
#pragma once

#include <filesystem>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/common/atomic_file.hpp"
#include "offline/log/gzip.hpp"
#include "offline/log/log.hpp"
#include "offline/log/log_metadata.hpp"

namespace tpf::offline {

/// Streaming writer. Rows go to a temporary file beside `path`; close() renames it into place,
/// so a crashed or abandoned recording never leaves a half-written log under `path`.
/// Numbers are written in shortest round-trip form (write → read gives the same doubles);
/// NaN is written as 'nan'. Metadata starts with '# tpf-log: 1'. A path ending in ".gz" is
/// written gzip-compressed as the rows come.
class LogWriter {
 public:
  /// Throws tpf::Error when the file cannot be created or a column name is invalid.
  LogWriter(std::filesystem::path path, LogMetadata meta, std::vector<std::string> columns);
  LogWriter(const LogWriter&) = delete;
  LogWriter& operator=(const LogWriter&) = delete;
  /// Not closed → the temporary is removed and nothing is left behind.
  ~LogWriter();

  /// Appends one sample, values in the order of the constructor's columns. Throws tpf::Error when
  /// the size is wrong, a value is infinite, or t (when there is a 't' column) does not increase.
  void write_row(std::span<const double> row);
  /// Flushes and renames the temporary into place (no fsync). Idempotent.
  void close();

  std::size_t rows_written() const { return rows_; }

 private:
  void flush();

  AtomicFile file_;
  std::unique_ptr<GzipStream> gzip_;  ///< set for a ".gz" path
  std::vector<std::string> columns_;
  std::string buffer_;
  int t_index_ = -1;
  double last_t_ = -std::numeric_limits<double>::infinity();
  std::size_t rows_ = 0;
};

/// Writes `log` (metadata, columns, values) to `path` atomically (temporary + rename). Formats in
/// parallel on two threads; a path ending in ".gz" is written gzip-compressed. Throws tpf::Error on
/// I/O failure, invalid names or infinite values.
void write_log(const std::filesystem::path& path, const Log& log);

}  // namespace tpf::offline
