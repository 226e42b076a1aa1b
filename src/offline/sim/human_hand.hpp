// The human of the "teaching" scenario: a hand that grabs one pad for a stroke and drags it
// towards a goal that moves at a steady speed to a reachable point (a spring–damper on the
// pad centre), always pressing into the pad, then lets go and pauses.
//   F = K_h·(g(t) − p) − D_h·ṗ, its normal part replaced by a push of at least 2 N, |F| ≤ F_max.
#pragma once

#include "offline/sim/random.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/twin_arm.hpp"

namespace tpf::offline {

struct HandForce {
  int pad = -1;                                           ///< 0-based, −1 when not touching
  Vector3<double> force_world = Vector3<double>::Zero();  ///< on the robot, N
  double area_cm2 = 1;
};

class HumanHand {
 public:
  HumanHand(const TeachingConfig& config, const TwinVector& lower, const TwinVector& upper,
            Random rng);
  /// The hand's force at time t (monotonic) on the arm at (q, q̇).
  HandForce update(const TwinArm& arm, double t, const TwinVector& q, const TwinVector& dq);

 private:
  void start_stroke(const TwinArm& arm, double t, const TwinVector& q);

  TeachingConfig config_;
  TwinVector lower_, upper_;
  Random rng_;
  bool holding_ = false;
  double next_change_ = 1.0;  // s
  int pad_ = -1;
  double area_ = 1.0;
  double stroke_start_ = 0.0;
  Vector3<double> start_ = Vector3<double>::Zero(), target_ = Vector3<double>::Zero();
  PadFrame frame_;  ///< update's pad frame, reused: no allocation per step
};

}  // namespace tpf::offline
