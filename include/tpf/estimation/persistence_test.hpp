// A persistence (k-in-a-row) test for an alarm that one sample must not raise, and the choice of
// k from a contact-free record for a wanted false-alarm rate.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <vector>

namespace tpf {

/// Alarm once a statistic has been outside its band for `samples` consecutive cycles, and for as
/// long as it stays outside: alarm_k = e_{k−n+1} ∧ … ∧ e_k (n = samples ≥ 1, n = 1: every
/// exceedance). The estimator's torque-only contact alarm (no pad on): a contact pushes steadily,
/// while the transition outliers of a contact-free arm are short. Allocation-free.
class PersistenceTest {
 public:
  explicit PersistenceTest(int samples = 1) noexcept : required_(std::max(samples, 1)) {}

  /// One cycle; `exceeded`: the statistic is outside its band now. Returns the alarm.
  bool update(bool exceeded) noexcept {
    run_ = exceeded ? std::min(run_ + 1, required_) : 0;
    return alarm();
  }
  void reset() noexcept { run_ = 0; }
  bool alarm() const noexcept { return run_ >= required_; }
  int required() const noexcept { return required_; }

 private:
  int required_;
  int run_ = 0;
};

/// Start-up: the smallest n in 1..max_samples whose PersistenceTest alarms on at most a share
/// `false_alarm_rate` of the cycles of a contact-free record (exceeded[k] ≠ 0: the statistic was
/// outside its band at cycle k): share(n) = #{k : exceeded[k−n+1..k] all set} / T. Returns
/// max_samples when no n up to it is low enough (and 1 for an empty record).
inline int persistence_for_false_alarm_rate(const Eigen::Ref<const Eigen::VectorXi>& exceeded,
                                            double false_alarm_rate, int max_samples) {
  max_samples = std::max(max_samples, 1);
  if (exceeded.size() == 0) return 1;
  // at_least[n] = number of cycles ending a run of at least n exceedances.
  std::vector<long> at_least(static_cast<std::size_t>(max_samples) + 2, 0);
  int run = 0;
  for (Eigen::Index k = 0; k < exceeded.size(); ++k) {
    run = exceeded[k] != 0 ? run + 1 : 0;
    ++at_least[static_cast<std::size_t>(std::min(run, max_samples + 1))];
  }
  for (int n = max_samples; n >= 0; --n)  // cumulative from the top
    at_least[static_cast<std::size_t>(n)] += at_least[static_cast<std::size_t>(n) + 1];
  const double cycles = static_cast<double>(exceeded.size());
  for (int n = 1; n <= max_samples; ++n)
    if (static_cast<double>(at_least[static_cast<std::size_t>(n)]) <= false_alarm_rate * cycles)
      return n;
  return max_samples;
}

}  // namespace tpf
