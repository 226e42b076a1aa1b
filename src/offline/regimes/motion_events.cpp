#include "offline/regimes/motion_events.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "tpf/common/error.hpp"

namespace tpf::offline {

MotionEvents count_motion_events(const Eigen::VectorXd& t, const Eigen::VectorXd& dq,
                                 Eigen::Index begin, Eigen::Index end, double reversal_velocity,
                                 const RegimeOptions& regimes) {
  if (t.size() != dq.size())
    throw Error("count_motion_events: dq has " + std::to_string(dq.size()) + " samples, t has " +
                std::to_string(t.size()));
  if (begin < 0 || end > t.size() || begin > end)
    throw Error("count_motion_events: rows [" + std::to_string(begin) + ", " + std::to_string(end) +
                ") outside the " + std::to_string(t.size()) + " samples");
  MotionEvents events;
  const Eigen::Index n = end - begin;
  if (n == 0) return events;
  const std::vector<Regime> labels =
      label_regimes(t.segment(begin, n), dq.segment(begin, n), regimes);
  int sign = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(k);
    if (labels[i] == Regime::StaticToKinetic &&
        (k == 0 || labels[i - 1] != Regime::StaticToKinetic))
      ++events.starts;
    const double v = dq[begin + k];
    if (!(std::abs(v) >= reversal_velocity)) continue;
    const int s = v > 0 ? 1 : -1;
    events.reversals += sign != 0 && s != sign ? 1 : 0;
    sign = s;
  }
  return events;
}

}  // namespace tpf::offline
