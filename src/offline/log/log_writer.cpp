#include "offline/log/log_writer.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

#include "offline/log/gzip.hpp"
#include "offline/log/log_text.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

constexpr std::size_t kFlushBytes = 1 << 20;

/// Formats rows [begin, end) of `values` (column-major) into `out`.
void format_rows(const Eigen::MatrixXd& values, Eigen::Index begin, Eigen::Index end,
                 std::string& out) {
  out.clear();
  std::vector<double> row(static_cast<std::size_t>(values.cols()));
  for (Eigen::Index r = begin; r < end; ++r) {
    for (Eigen::Index c = 0; c < values.cols(); ++c)
      row[static_cast<std::size_t>(c)] = values(r, c);
    log_text::append_row(out, row);
  }
}

}  // namespace

LogWriter::LogWriter(std::filesystem::path path, LogMetadata meta, std::vector<std::string> columns)
    : file_(std::move(path)), columns_(std::move(columns)) {
  if (has_gzip_suffix(file_.path().string())) gzip_ = std::make_unique<GzipStream>();
  buffer_ = log_text::prelude(meta, columns_, file_.path().string());
  const auto t = std::find(columns_.begin(), columns_.end(), "t");
  if (t != columns_.end()) t_index_ = static_cast<int>(t - columns_.begin());
  buffer_.reserve(kFlushBytes + 4096);
}

LogWriter::~LogWriter() = default;

void LogWriter::write_row(std::span<const double> row) {
  const std::string path = file_.path().string();
  if (file_.committed()) throw Error::at(path, 0, "", "write_row after close");
  if (row.size() != columns_.size())
    throw Error::at(path, 0, "",
                    "row " + std::to_string(rows_ + 1) + " has " + std::to_string(row.size()) +
                        " values for " + std::to_string(columns_.size()) + " columns");
  log_text::check_finite(row, columns_, path);
  if (t_index_ >= 0) {
    const double t = row[static_cast<std::size_t>(t_index_)];
    if (!(t > last_t_))
      throw Error::at(
          path, 0, "t",
          "row " + std::to_string(rows_ + 1) + ": t = " + std::to_string(t) + " does not increase");
    last_t_ = t;
  }
  log_text::append_row(buffer_, row);
  ++rows_;
  if (buffer_.size() >= kFlushBytes) flush();
}

void LogWriter::flush() {
  file_.write(gzip_ ? gzip_->write(buffer_) : std::string_view(buffer_));
  buffer_.clear();
}

void LogWriter::close() {
  if (file_.committed()) return;
  flush();
  if (gzip_) file_.write(gzip_->finish());
  file_.commit();
}

void write_log(const std::filesystem::path& path, const Log& log) {
  if (static_cast<std::size_t>(log.values.cols()) != log.columns.size())
    throw Error::at(path.string(), 0, "",
                    std::to_string(log.columns.size()) + " column names for " +
                        std::to_string(log.values.cols()) + " columns");
  for (Eigen::Index c = 0; c < log.values.cols(); ++c)
    if (log.values.col(c).array().isInf().any())
      throw Error::at(path.string(), 0, log.columns[static_cast<std::size_t>(c)],
                      "cannot write an infinite value (use NaN for missing)");
  const int t = log.column("t");
  if (t >= 0)
    for (Eigen::Index r = 1; r < log.values.rows(); ++r)
      if (!(log.values(r, t) > log.values(r - 1, t)))
        throw Error::at(path.string(), 0, "t",
                        "row " + std::to_string(r + 1) + " does not increase");

  // A path ending in ".gz" gets the same text gzip-compressed.
  std::unique_ptr<GzipStream> gzip;
  if (has_gzip_suffix(path.string())) gzip = std::make_unique<GzipStream>();
  AtomicFile file(path);
  const auto emit = [&](std::string_view piece) { file.write(gzip ? gzip->write(piece) : piece); };
  emit(log_text::prelude(log.meta, log.columns, path.string()));
  // Two threads format alternate blocks of rows; the main thread writes them in order.
  constexpr Eigen::Index kBlock = 32768;
  std::string first, second;
  for (Eigen::Index begin = 0; begin < log.values.rows(); begin += 2 * kBlock) {
    const Eigen::Index middle = std::min(begin + kBlock, log.values.rows());
    const Eigen::Index end = std::min(middle + kBlock, log.values.rows());
    if (end > middle) {
      std::thread helper([&] { format_rows(log.values, middle, end, second); });
      format_rows(log.values, begin, middle, first);
      helper.join();
    } else {
      format_rows(log.values, begin, middle, first);
      second.clear();
    }
    emit(first);
    emit(second);
  }
  if (gzip) file.write(gzip->finish());
  file.commit();
}

}  // namespace tpf::offline
