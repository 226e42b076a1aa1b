// Timing statistics of a periodic loop: wake-up lateness against the absolute deadline
// (period jitter), bus time and estimator time per cycle, as p50 / p99 / max.
#pragma once

#include <cstdint>
#include <vector>

namespace tpf::arm {

struct TimingSummary {
  std::uint64_t cycles = 0;
  double lateness_p50_s = 0, lateness_p99_s = 0, lateness_max_s = 0;
  double bus_p50_s = 0, bus_p99_s = 0, bus_max_s = 0;
  double estimator_p50_s = 0, estimator_p99_s = 0, estimator_max_s = 0;
};

class LoopStatistics {
 public:
  /// Keeps the last `capacity` cycles for percentiles (allocated here, once); max over all.
  explicit LoopStatistics(std::size_t capacity = 1 << 16);
  /// Per cycle, no allocation.
  void record(double lateness_s, double bus_s, double estimator_s = 0.0) noexcept;
  /// Percentiles by nth_element over the kept window (allocates: call after the loop).
  TimingSummary summarize() const;

 private:
  std::vector<double> lateness_, bus_, estimator_;
  std::uint64_t count_ = 0;
  double lateness_max_ = 0.0, bus_max_ = 0.0, estimator_max_ = 0.0;
};

}  // namespace tpf::arm
