// The mechanical plant of the twin: rigid-body arm (with armature) + motor friction + position-
// dependent undeclared torques, advanced at the fixed inner rate.
//
// Integration per step of length h (Lie splitting):
//  1. RK4 of M(q)q̈ + C(q,q̇)q̇ + G(q) = τ_in + τ_pos(q), with τ_in (motor + external torques)
//     held over the step and τ_pos (ripple, spring) evaluated at each stage → (q*, q̇*).
//  2. Friction as a torque held over the step, implicit in its velocity change δ = −h·M⁻¹·τ_f:
//       M(q*)·δ + h·τ_f(v, z) = 0,   v = v0 + δ/2,   v0 = (q* − q_k)/h,
//     solved by Newton's method. A torque held over h moves the joint by h·δ/2, so v is exactly
//     the step's mean velocity; F is the LuGre torque with the exponential bristle update over h
//     at that velocity (stable for any bristle stiffness). Then q ← q* + h·δ/2, q̇ ← q̇* + δ,
//     z ← z(v). The bristles absorb exactly the displacement the joint made, and a sticking
//     joint keeps q̇ = 0 (no creep, no velocity bias).
// Friction is the motors': motor m's curve F_m (its bristle z_m, its load term on |G_m(q)|, its
// viscous scale) on its velocity u_m = (C·v)_m at the output scale, acting on the joints as
// τ_f = Cᵀ·F(C·v), C the arm's coupling (TwinArm::coupling). The Newton matrix is then
// M + ½h·Cᵀ·diag(max(∂F_m/∂u_m, 0))·C, symmetric positive definite like M. Without a coupling
// (C = I) F_j depends on joint j only and the step is the uncoupled twin's, bit for bit (its own
// code path: M + ½h·diag(max(∂F/∂v, 0))).
// With friction off step 2 vanishes and the scheme is plain RK4 (energy-conserving to O(h⁴)).
#pragma once

#include "offline/sim/scenario.hpp"
#include "offline/sim/twin_arm.hpp"
#include "offline/sim/twin_friction.hpp"
#include "offline/sim/twin_linear_algebra.hpp"

namespace tpf::offline {

class TwinPlant {
 public:
  /// `friction` and the effects' per-joint vectors have one entry per joint of `arm`.
  TwinPlant(const TwinArm& arm, const TwinFriction& friction, const EffectsConfig& effects,
            double dt);

  /// Sets the state (bristles relaxed).
  void reset(const TwinVector& q, const TwinVector& dq);

  /// Advances one step with τ_in (N·m) held; `viscous_scale` multiplies b (temperature drift).
  /// Allocation-free after the first step: its vectors and matrices are members, sized once.
  void step(const TwinVector& tau_in, const TwinVector& viscous_scale);

  const TwinVector& q() const { return q_; }
  const TwinVector& dq() const { return dq_; }
  /// Joint acceleration over the last step, (q̇_k+1 − q̇_k)/h.
  const TwinVector& ddq() const { return ddq_; }
  /// Friction torque on the joints applied during the last step, Cᵀ·F (N·m, opposes motion:
  /// enters M q̈ with −).
  const TwinVector& friction() const { return friction_; }
  /// The motors' friction F over the last step at the output scale (N·m per motor); friction()
  /// without a coupling.
  const TwinVector& motor_friction() const { return coupled_ ? motor_friction_ : friction_; }
  /// LuGre deflection z per motor (per joint without a coupling), rad at the output scale.
  const TwinVector& bristles() const { return bristles_; }
  /// Torque of the position-dependent undeclared effects (ripple + spring) at q, N·m.
  TwinVector position_torque(const TwinVector& q) const;
  /// position_torque(q) into `tau` (resized to N; allocation-free at that size). `tau` must not
  /// be `q`.
  void position_torque(const TwinVector& q, TwinVector& tau) const;
  /// Total mechanical energy T + V (J).
  double energy() const { return arm_.energy(q_, dq_); }
  const TwinArm& arm() const { return arm_; }

 private:
  /// q̈ at (q, q̇) under τ_in + τ_pos(q), into `ddq`; uses tau_stage_.
  void acceleration(const TwinVector& q, const TwinVector& dq, const TwinVector& tau_in,
                    TwinVector& ddq);
  double joint_friction(int j, double v, double abs_gravity, double viscous_scale,
                        double* z_out) const;
  /// Step 2, each joint's friction on its own velocity: δ in delta_, friction_ and bristles_ set.
  void joint_friction_step(const TwinVector& abs_gravity, const TwinVector& viscous_scale);
  /// Step 2 with coupled motors: τ_f = Cᵀ·F(C·v); δ in delta_, friction_ and bristles_ set.
  void coupled_friction_step(const TwinVector& abs_gravity, const TwinVector& viscous_scale);

  TwinArm arm_;
  TwinFriction friction_parameters_;
  EffectsConfig effects_;
  double dt_;
  int n_;         ///< joints
  bool coupled_;  ///< arm_.coupled(): friction on the motors' coordinates C·v
  TwinVector q_, dq_, ddq_, friction_;
  TwinVector bristles_;     ///< LuGre deflection z per motor (= joint without coupling), rad
  TwinLdlt newton_factor_;  ///< of the friction step's Newton matrix M + ½h·∂F/∂v
  // step()'s workspace, sized once (the names of step's quantities).
  TwinVector q0_, dq0_, a1_, a2_, a3_, a4_, v2_, v3_, v4_;
  TwinVector q_stage_, tau_stage_;  ///< an RK4 stage's q and τ_in + τ_pos(q)
  TwinVector abs_gravity_, v0_, delta_, force_, slope_, newton_step_;
  TwinMatrix mass_, newton_matrix_;  ///< M(q*) and M + ½h·Cᵀ·max(∂F/∂u, 0)·C
  // The coupled step's workspace: motor velocities u = C·v, motor friction F(u).
  TwinVector motor_velocity_, motor_friction_;
};

}  // namespace tpf::offline
