#include "arm/csv_log_writer.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <ctime>

#include "tpf/common/error.hpp"

namespace tpf::arm {

CsvLogWriter::CsvLogWriter(const std::string& path, std::size_t joints, std::size_t pads,
                           const LogMetadata& metadata, std::size_t capacity)
    : joints_(std::min(joints, kMaxJoints)), pads_(std::min(pads, kMaxPads)), ring_(capacity) {
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) throw Error::at(path, 0, "log", std::strerror(errno));
  std::fprintf(file_, "# tpf-log: 1\n# robot: %s\n# rate_hz: %g\n", metadata.robot.c_str(),
               metadata.rate_hz);
  if (!metadata.note.empty()) std::fprintf(file_, "# note: %s\n", metadata.note.c_str());
  std::fputs("t", file_);
  for (const char* name : {"q", "dq", "i"})
    for (std::size_t j = 1; j <= joints_; ++j)
      std::fprintf(file_, ",%s%zu", name, j);
  for (std::size_t k = 1; k <= pads_; ++k)
    std::fprintf(file_, ",p%zu", k);
  std::fputc('\n', file_);
  thread_ = std::thread([this] {
    while (running_.load()) {
      drain();
      const timespec pause{0, 5'000'000};
      clock_nanosleep(CLOCK_MONOTONIC, 0, &pause, nullptr);
    }
    drain();
  });
}

CsvLogWriter::~CsvLogWriter() {
  close();
}

void CsvLogWriter::close() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
}

bool CsvLogWriter::push(const CycleSample& sample) noexcept {
  const std::uint64_t head = head_.load(std::memory_order_relaxed);
  if (head - tail_.load(std::memory_order_acquire) >= ring_.size()) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  ring_[head % ring_.size()] = sample;
  head_.store(head + 1, std::memory_order_release);
  return true;
}

void CsvLogWriter::drain() {
  std::uint64_t tail = tail_.load(std::memory_order_relaxed);
  const std::uint64_t head = head_.load(std::memory_order_acquire);
  for (; tail < head; ++tail) {
    write_row(ring_[tail % ring_.size()]);
    tail_.store(tail + 1, std::memory_order_release);
  }
  std::fflush(file_);
}

void CsvLogWriter::write_row(const CycleSample& s) {
  // Missing values are written as "nan" (log-format.md): never invented.
  const auto put = [&](bool valid, double v, const char* format) {
    if (valid && std::isfinite(v))
      std::fprintf(file_, format, v);
    else
      std::fputs(",nan", file_);
  };
  std::fprintf(file_, "%.6f", s.t);
  for (std::size_t j = 0; j < joints_; ++j)
    put(s.motors_valid, s.q[j], ",%.9g");
  for (std::size_t j = 0; j < joints_; ++j)
    put(s.motors_valid, s.dq[j], ",%.9g");
  for (std::size_t j = 0; j < joints_; ++j)
    put(s.motors_valid, s.i[j], ",%.0f");
  for (std::size_t k = 0; k < pads_; ++k)
    put(s.pads_valid && k < s.pads, s.p[k], ",%.5g");
  std::fputc('\n', file_);
  written_.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace tpf::arm
