#include "arm/loop_statistics.hpp"

#include <algorithm>

namespace tpf::arm {
namespace {

/// q-quantile (nearest rank) of `v`, reordering it.
double quantile(std::vector<double>& v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

LoopStatistics::LoopStatistics(std::size_t capacity)
    : lateness_(capacity), bus_(capacity), estimator_(capacity) {}

void LoopStatistics::record(double lateness_s, double bus_s, double estimator_s) noexcept {
  const std::size_t slot = count_ % lateness_.size();
  lateness_[slot] = lateness_s;
  bus_[slot] = bus_s;
  estimator_[slot] = estimator_s;
  lateness_max_ = std::max(lateness_max_, lateness_s);
  bus_max_ = std::max(bus_max_, bus_s);
  estimator_max_ = std::max(estimator_max_, estimator_s);
  ++count_;
}

TimingSummary LoopStatistics::summarize() const {
  const auto n = static_cast<std::ptrdiff_t>(std::min<std::uint64_t>(count_, lateness_.size()));
  std::vector<double> late(lateness_.begin(), lateness_.begin() + n);
  std::vector<double> bus(bus_.begin(), bus_.begin() + n);
  std::vector<double> estimator(estimator_.begin(), estimator_.begin() + n);
  TimingSummary s;
  s.cycles = count_;
  s.lateness_p50_s = quantile(late, 0.50);
  s.lateness_p99_s = quantile(late, 0.99);
  s.lateness_max_s = lateness_max_;
  s.bus_p50_s = quantile(bus, 0.50);
  s.bus_p99_s = quantile(bus, 0.99);
  s.bus_max_s = bus_max_;
  s.estimator_p50_s = quantile(estimator, 0.50);
  s.estimator_p99_s = quantile(estimator, 0.99);
  s.estimator_max_s = estimator_max_;
  return s;
}

}  // namespace tpf::arm
