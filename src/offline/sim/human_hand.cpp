#include "offline/sim/human_hand.hpp"

#include <algorithm>

namespace tpf::offline {

namespace {
constexpr double kMinimumPush = 2.0;  // N, the hand always presses into the pad while holding
}

HumanHand::HumanHand(const TeachingConfig& config, const TwinVector& lower, const TwinVector& upper,
                     Random rng)
    : config_(config), lower_(lower), upper_(upper), rng_(std::move(rng)) {
  frame_.linear_jacobian.setZero(3, lower.size());
}

void HumanHand::start_stroke(const TwinArm& arm, double t, const TwinVector& q) {
  // Grab a pad on links 2..N (link 1 barely moves the rest of the arm).
  std::vector<int> candidates;
  for (int k = 0; k < arm.pad_count(); ++k)
    if (arm.pad_frame(q, k).link >= 2) candidates.push_back(k);
  if (candidates.empty()) return;
  pad_ = candidates[rng_.index(static_cast<int>(candidates.size()))];
  TwinVector goal_q(q.size());
  for (int j = 0; j < q.size(); ++j)
    goal_q[j] = rng_.uniform(lower_[j], upper_[j]);
  start_ = arm.pad_frame(q, pad_).centre;
  target_ = arm.pad_frame(goal_q, pad_).centre;
  area_ = rng_.uniform(3.0, 12.0);
  stroke_start_ = t;
  holding_ = true;
  next_change_ = t + rng_.uniform(config_.stroke_min_s, config_.stroke_max_s);
}

HandForce HumanHand::update(const TwinArm& arm, double t, const TwinVector& q,
                            const TwinVector& dq) {
  if (t >= next_change_) {
    if (holding_) {
      holding_ = false;
      next_change_ = t + rng_.uniform(config_.pause_min_s, config_.pause_max_s);
    } else {
      start_stroke(arm, t, q);
    }
  }
  HandForce out;
  if (!holding_) return out;
  arm.pad_frame(q, pad_, frame_);
  const PadFrame& pad = frame_;
  const Vector3<double> path = target_ - start_;
  const double length = path.norm();
  const double travelled = std::min(length, config_.goal_speed * (t - stroke_start_));
  const Vector3<double> goal =
      length > 0 ? Vector3<double>(start_ + path * (travelled / length)) : start_;
  const Vector3<double> velocity = arm.pad_velocity(pad, dq);
  Vector3<double> f =
      config_.hand_stiffness * (goal - pad.centre) - config_.hand_damping * velocity;
  const Vector3<double> n = pad.rotation.col(2);
  const double push = std::max(kMinimumPush, -f.dot(n));
  f = f - f.dot(n) * n - push * n;
  if (f.norm() > config_.max_force_n) f *= config_.max_force_n / f.norm();
  out.pad = pad_;
  out.force_world = f;
  out.area_cm2 = area_;
  return out;
}

}  // namespace tpf::offline
