// Scripted hand contacts for the "static-contacts" scenario: the arm moves to a pose, holds it,
// and a hand pushes on one pad at a time — normal force plus shear, with a smooth ramp up, a
// hold and a ramp down — then the arm moves on to the next pose.
#pragma once

#include <vector>

#include "offline/sim/min_jerk_schedule.hpp"
#include "offline/sim/random.hpp"
#include "offline/sim/scenario.hpp"

namespace tpf::offline {

/// One push. The force on the robot in the pad's contact frame (x, y tangent, z = outward
/// normal) is profile(t)·(shear_x, shear_y, −normal): a push acts against the outward normal.
struct ContactEvent {
  int pad = 0;  ///< 0-based
  double t_on = 0, t_full = 0, t_release = 0, t_off = 0;
  double normal_n = 0, shear_x_n = 0, shear_y_n = 0;
  double area_cm2 = 1;
};

/// The force acting at one instant (none when pad < 0).
struct ContactSample {
  int pad = -1;
  Vector3<double> force_contact = Vector3<double>::Zero();  ///< contact frame, N
  double area_cm2 = 1;
};

class ContactScript {
 public:
  void add(const ContactEvent& event) { events_.push_back(event); }
  /// The contact at time t (t must not decrease between calls).
  ContactSample at(double t);
  const std::vector<ContactEvent>& events() const { return events_; }

 private:
  std::vector<ContactEvent> events_;
  std::size_t cursor_ = 0;
};

struct StaticContactPlan {
  MinJerkSchedule poses;
  ContactScript contacts;
};

/// Poses drawn uniformly in [lower, upper], reached in `pose_move_s`; pushes_per_pose pushes on
/// random pads (of `pad_count`) at each pose, until `duration`.
StaticContactPlan make_static_contact_plan(const ContactConfig& config, const TwinVector& start,
                                           const TwinVector& lower, const TwinVector& upper,
                                           int pad_count, double duration, Random& rng);

}  // namespace tpf::offline
