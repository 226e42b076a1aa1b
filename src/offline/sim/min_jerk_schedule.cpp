#include "offline/sim/min_jerk_schedule.hpp"

#include <algorithm>

namespace tpf::offline {

void MinJerkSchedule::append(int j, double q1, double duration) {
  const auto k = static_cast<std::size_t>(j);
  segments_[k].push_back({end_t_[k], end_t_[k] + duration, end_q_[j], q1});
  end_t_[k] += duration;
  end_q_[j] = q1;
}

void MinJerkSchedule::evaluate(double t, TwinVector& q, TwinVector& dq) {
  q.resize(end_q_.size());
  dq.resize(end_q_.size());
  for (int j = 0; j < end_q_.size(); ++j) {
    const auto& segs = segments_[static_cast<std::size_t>(j)];
    std::size_t& c = cursor_[static_cast<std::size_t>(j)];
    while (c < segs.size() && t >= segs[c].t1)
      ++c;
    if (c >= segs.size()) {
      q[j] = end_q_[j];
      dq[j] = 0.0;
      continue;
    }
    const Segment& s = segs[c];
    const double T = s.t1 - s.t0;
    const double tau = std::max(0.0, (t - s.t0) / T);
    const double tau2 = tau * tau, tau3 = tau2 * tau;
    const double shape = tau3 * (10.0 - 15.0 * tau + 6.0 * tau2);
    const double rate = 30.0 * tau2 * (1.0 - 2.0 * tau + tau2) / T;
    q[j] = s.q0 + (s.q1 - s.q0) * shape;
    dq[j] = (s.q1 - s.q0) * rate;
  }
}

}  // namespace tpf::offline
