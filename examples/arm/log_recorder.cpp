#include "arm/log_recorder.hpp"

#include <cmath>
#include <ctime>
#include <limits>

#include "offline/log/log.hpp"
#include "tpf/common/error.hpp"

namespace tpf::arm {

std::vector<std::string> recorded_column_names(const RecordedColumns& c) {
  std::vector<std::string> names{"t"};
  for (const char* quantity : {"q", "dq", "i"})
    for (std::size_t j = 1; j <= c.joints; ++j)
      names.push_back(offline::indexed_name(quantity, static_cast<int>(j)));
  for (std::size_t k = 1; k <= c.pads; ++k)
    names.push_back(offline::indexed_name("p", static_cast<int>(k)));
  if (c.estimates) {
    for (std::size_t j = 1; j <= c.joints; ++j)
      names.push_back(offline::indexed_name("est_tau_ext", static_cast<int>(j)));
    for (const char* name : {"est_contact", "est_pad", "est_fx", "est_fy", "est_fz", "est_status"})
      names.emplace_back(name);
  }
  return names;
}

namespace {

RecordedColumns bounded(RecordedColumns c) {
  c.joints = std::min(c.joints, kMaxJoints);
  c.pads = std::min(c.pads, kMaxPads);
  return c;
}

}  // namespace

LogRecorder::LogRecorder(const std::string& path, RecordedColumns columns,
                         offline::LogMetadata metadata, std::size_t capacity)
    : writer_(path, std::move(metadata), recorded_column_names(bounded(columns))),
      columns_(bounded(columns)),
      row_(recorded_column_names(columns_).size()),
      ring_(capacity) {
  thread_ = std::thread([this] {
    while (running_.load()) {
      drain();
      const timespec pause{0, 5'000'000};
      clock_nanosleep(CLOCK_MONOTONIC, 0, &pause, nullptr);
    }
    drain();
  });
}

LogRecorder::~LogRecorder() {
  try {
    close();
  } catch (const Error&) {  // counted in rows_failed(); a destructor does not throw
  }
}

void LogRecorder::close() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
  if (failed_.load() != 0)
    throw Error::at("log", 0, "", error_ + " (" + std::to_string(failed_.load()) + " rows lost)");
  writer_.close();
}

bool LogRecorder::push(const CycleSample& sample) noexcept {
  const std::uint64_t head = head_.load(std::memory_order_relaxed);
  if (head - tail_.load(std::memory_order_acquire) >= ring_.size()) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return false;
  }
  ring_[head % ring_.size()] = sample;
  head_.store(head + 1, std::memory_order_release);
  return true;
}

void LogRecorder::drain() {
  std::uint64_t tail = tail_.load(std::memory_order_relaxed);
  const std::uint64_t head = head_.load(std::memory_order_acquire);
  for (; tail < head; ++tail) {
    write(ring_[tail % ring_.size()]);
    tail_.store(tail + 1, std::memory_order_release);
  }
}

void LogRecorder::write(const CycleSample& s) {
  if (failed_.load() != 0) {  // the writer failed: count, do not retry row by row
    failed_.fetch_add(1);
    return;
  }
  fill_row(s);
  try {
    writer_.write_row(row_);
    written_.fetch_add(1, std::memory_order_relaxed);
  } catch (const Error& e) {
    error_ = e.what();
    failed_.fetch_add(1);
  }
}

void LogRecorder::fill_row(const CycleSample& s) {
  // Missing values are NaN (log-format.md): never invented.
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const auto value = [](bool valid, double v) { return valid && std::isfinite(v) ? v : nan; };
  std::size_t c = 0;
  row_[c++] = s.t;
  for (const auto* quantity : {&s.q, &s.dq, &s.i})
    for (std::size_t j = 0; j < columns_.joints; ++j)
      row_[c++] = value(s.motors_valid, (*quantity)[j]);
  for (std::size_t k = 0; k < columns_.pads; ++k)
    row_[c++] = value(s.pads_valid && k < s.pads, static_cast<double>(s.p[k]));
  if (!columns_.estimates) return;
  const CycleEstimate& e = s.estimate;
  for (std::size_t j = 0; j < columns_.joints; ++j)
    row_[c++] = value(e.present, e.external_torque_nm[j]);
  row_[c++] = e.present ? (e.contact ? 1.0 : 0.0) : nan;
  row_[c++] = e.present ? static_cast<double>(e.contact_pad + 1) : nan;
  for (const double f : e.force_world_n)
    row_[c++] = value(e.present, f);
  row_[c++] = static_cast<double>(e.status);
}

}  // namespace tpf::arm
