// The teaching controller the twin closes the loop with: joint-space admittance on a simple
// external-torque estimate from the motor currents, sending position references to the drives.
//   τ̂ = −(K_t·i − G(q) − F_nom(q̇)) − b,   b frozen while a pad is pressed (else tracked, 0.5 s)
//   M_a·q̈_a + D_a·q̇_a = deadband(τ̂),   q_ref += q̇_a·Δt (inside the joint range)
// The drive receives the goal as a first-order hold over the host cycle (`goal`), as a PH54 run
// with a profile velocity moves its set-point between writes.
// F_nom is the memoryless smooth Stribeck curve of the friction file, so this controller is
// deliberately the "nominal model" kind a user would start with. With coupled motors (the
// nominal arm's coupling C) the currents are the motors': τ = Cᵀ·K_t·i and F_nom = Cᵀ·F(C·q̇).
#pragma once

#include "offline/sim/scenario.hpp"
#include "offline/sim/twin_arm.hpp"
#include "offline/sim/twin_friction.hpp"

namespace tpf::offline {

class AdmittanceController {
 public:
  /// `nominal_friction`'s Stribeck curves (its load terms are dropped) and the vectors have one
  /// entry per joint.
  AdmittanceController(const TeachingConfig& config, const TwinFriction& nominal_friction,
                       const TwinVector& start, const TwinVector& lower, const TwinVector& upper);

  /// One host cycle with the measurements (q rad, q̇ rad/s, i mA), the largest pad reading (kPa).
  void update(const TwinArm& nominal, const TwinVector& q, const TwinVector& dq,
              const TwinVector& current_ma, double max_pad_kpa, double dt);

  /// One host cycle following an external estimate τ̂_ext [N·m] (already dead-banded by its
  /// estimator) instead of the built-in one; the arm still moves only while a pad is pressed.
  void follow(const TwinVector& tau_ext, double max_pad_kpa, double dt);

  /// The goal the drive follows a time s ≥ 0 after the host's last write t_k (first-order hold):
  ///   q_goal(t_k + s) = clamp(q_ref,k + q̇_ref,k·s, lower, upper),   q̇_goal = q̇_ref,k
  /// (q̇_goal = 0 on a joint held at its limit). Holding q_ref,k instead makes the drive's position
  /// loop see a staircase: its command falls by K_p·q̇·s within each cycle, so current and q̈ carry
  /// a host-rate sawtooth that rows sampled at one phase alias to a bias ≈ −2.3 s⁻¹·q̇ in q̈ — a
  /// drive input the scenarios with a continuous schedule (training, calibration) never give.
  void goal(double since_write, TwinVector& q_goal, TwinVector& dq_goal) const;

  const TwinVector& q_ref() const { return q_ref_; }
  const TwinVector& dq_ref() const { return dq_ref_; }

 private:
  /// M_a·q̈_a + D_a·q̇_a = τ, q_ref += q̇_a·Δt inside the joint range.
  void integrate(const TwinVector& tau, double dt);
  /// F_nom(q̇) of every joint: the smooth memoryless Stribeck curve without load terms.
  TwinVector nominal_friction(const TwinVector& dq) const;

  TeachingConfig config_;
  TwinFriction friction_;
  TwinVector lower_, upper_;
  TwinVector q_ref_, dq_ref_, baseline_;
  bool baseline_ready_ = false;
};

}  // namespace tpf::offline
