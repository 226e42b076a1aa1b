#include "offline/sim/contact_script.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tpf::offline {

namespace {
// Minimum-jerk ramp from 0 to 1 over τ ∈ [0, 1].
double ramp(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10.0 - 15.0 * tau + 6.0 * tau * tau);
}
}  // namespace

ContactSample ContactScript::at(double t) {
  while (cursor_ < events_.size() && t >= events_[cursor_].t_off)
    ++cursor_;
  ContactSample s;
  if (cursor_ >= events_.size()) return s;
  const ContactEvent& e = events_[cursor_];
  if (t < e.t_on) return s;
  const double profile = t < e.t_full ? ramp((t - e.t_on) / (e.t_full - e.t_on))
                         : t < e.t_release
                             ? 1.0
                             : 1.0 - ramp((t - e.t_release) / (e.t_off - e.t_release));
  s.pad = e.pad;
  s.force_contact = profile * Vector3<double>(e.shear_x_n, e.shear_y_n, -e.normal_n);
  s.area_cm2 = e.area_cm2;
  return s;
}

StaticContactPlan make_static_contact_plan(const ContactConfig& c, const TwinVector& start,
                                           const TwinVector& lower, const TwinVector& upper,
                                           int pad_count, double duration, Random& rng) {
  StaticContactPlan plan{MinJerkSchedule(start), {}};
  double t = 0.0;
  constexpr double kSettle = 1.0;  // s of stillness before the first push at a pose
  bool first = true;
  while (t < duration) {
    if (!first) {
      for (int j = 0; j < start.size(); ++j)
        plan.poses.append(j, rng.uniform(lower[j], upper[j]), c.pose_move_s);
      t += c.pose_move_s;
    }
    first = false;
    double hold = kSettle;
    for (int k = 0; k < c.pushes_per_pose && pad_count > 0; ++k) {
      ContactEvent e;
      e.pad = rng.index(pad_count);
      e.t_on = t + hold + rng.uniform(c.pause_min_s, c.pause_max_s);
      e.t_full = e.t_on + c.ramp_s;
      e.t_release = e.t_full + rng.uniform(c.hold_min_s, c.hold_max_s);
      e.t_off = e.t_release + c.ramp_s;
      e.normal_n = rng.uniform(c.force_min_n, c.force_max_n);
      const double shear = e.normal_n * rng.uniform(0.0, c.shear_ratio_max);
      const double angle = rng.uniform(0.0, 2.0 * std::numbers::pi);
      e.shear_x_n = shear * std::cos(angle);
      e.shear_y_n = shear * std::sin(angle);
      e.area_cm2 = rng.uniform(c.area_min_cm2, c.area_max_cm2);
      plan.contacts.add(e);
      hold += e.t_off - (t + hold);
    }
    hold += 0.5;
    for (int j = 0; j < start.size(); ++j)
      plan.poses.append(j, plan.poses.end_position(j), hold);
    t += hold;
  }
  return plan;
}

}  // namespace tpf::offline
