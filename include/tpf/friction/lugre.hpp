// LuGre friction: a bristle model with memory that produces pre-sliding (spring-like) motion,
// break-away at the static friction level, and stick–slip / hysteresis; in steady sliding it
// reduces exactly to the Stribeck + viscous curve of stribeck.hpp.
//
//   ż = q̇ − σ0·|q̇|·z / g(q̇),      τ_f = σ0·z + σ1·ż + (b + α_v|G|)·q̇,
//   g(q̇) = τ_c + α_c|G| + (τ_s − τ_c)·exp(−|q̇/q̇_s|^δ)            (Canudas de Wit et al., 1995)
//
// z is the mean bristle deflection (rad), σ0 the bristle (pre-sliding) stiffness per rad, σ1 the
// bristle damping per rad/s. Steady state: ż = 0 ⇒ z = g·sgn(q̇)/σ0 ⇒ τ_f = Stribeck.
#pragma once

#include <cmath>

#include "tpf/friction/stribeck.hpp"

namespace tpf {

/// Stribeck curve plus the bristle stiffness σ0 and damping σ1 of each joint.
/// At Eigen::Dynamic the vectors start empty: resize(n) gives n joints the defaults below.
template <typename S, int N>
struct LuGreParameters {
  using Vector = JointVector<S, N>;
  StribeckParameters<S, N> stribeck;
  Vector bristle_stiffness = stiffness_or_empty();   ///< σ0 > 0
  Vector bristle_damping = zero_or_empty<Vector>();  ///< σ1 ≥ 0

  /// Sizes every coefficient for n joints with the defaults (σ0 = 1e4, σ1 = 0).
  void resize(int n) {
    stribeck.resize(n);
    bristle_stiffness = Vector::Constant(n, kDefaultStiffness);
    bristle_damping = Vector::Zero(n);
  }

 private:
  static constexpr S kDefaultStiffness = S(1e4);
  static Vector stiffness_or_empty() {
    if constexpr (N == Eigen::Dynamic)
      return Vector();
    else
      return Vector::Constant(kDefaultStiffness);
  }
};

/// The same parameters with joint count `To` and scalar `ToS` (see the Stribeck cast).
template <int To, typename ToS, typename S, int From>
LuGreParameters<ToS, To> joint_count_cast(const LuGreParameters<S, From>& from) {
  LuGreParameters<ToS, To> to;
  to.stribeck = joint_count_cast<To, ToS>(from.stribeck);
  to.bristle_stiffness = from.bristle_stiffness.template cast<ToS>();
  to.bristle_damping = from.bristle_damping.template cast<ToS>();
  return to;
}

/// The memory of the model: bristle deflection z of each joint, rad (at Eigen::Dynamic sized by
/// the caller: LuGreState{JointVector::Zero(n)}).
template <typename S, int N>
struct LuGreState {
  JointVector<S, N> z = zero_or_empty<JointVector<S, N>>();
};

/// One joint's result of a step: new deflection and the friction torque over the step.
template <typename S>
struct LuGreJointStep {
  S z;       ///< deflection at the end of the step
  S torque;  ///< τ_f = σ0·z_end + σ1·(z_end − z_start)/dt + (b + α_v|G|)·q̇
};

/// Advances joint j's deflection by dt at constant velocity q̇ with the exact solution of the
/// (then linear) bristle equation, which is unconditionally stable however stiff σ0 is:
///   z(dt) = z_ss + (z0 − z_ss)·exp(−σ0|q̇|dt/g),   z_ss = sgn(q̇)·g(q̇)/σ0.
/// ż is taken as the step average (z(dt) − z0)/dt.
template <typename S, int N>
LuGreJointStep<S> lugre_joint_step(const LuGreParameters<S, N>& p, int j, S z0, S dq, S abs_gravity,
                                   S dt) {
  using std::abs, std::exp;
  const S sigma0 = p.bristle_stiffness[j];
  const S level = stribeck_level(p.stribeck, j, dq, abs_gravity);
  S z = z0;
  if (dq != S(0) && level > S(0)) {
    const S z_ss = (dq > S(0) ? level : -level) / sigma0;
    z = z_ss + (z0 - z_ss) * exp(-sigma0 * abs(dq) * dt / level);
  } else if (dq != S(0)) {
    z = S(0);  // no friction level: bristles relax at once
  }
  const S torque = sigma0 * z + p.bristle_damping[j] * (z - z0) / dt +
                   viscous_coefficient(p.stribeck, j, abs_gravity) * dq;
  return {z, torque};
}

/// Advances every joint by dt (see lugre_joint_step) and returns the friction torques; updates
/// `state`. Allocation-free. |G_j(q)| in `abs_gravity` (zeros for the load-free model).
template <typename S, int N>
JointVector<S, N> lugre_step(const LuGreParameters<S, N>& p, LuGreState<S, N>& state,
                             const JointVector<S, N>& dq, const JointVector<S, N>& abs_gravity,
                             S dt) {
  JointVector<S, N> tau;
  tau.resize(dq.size());
  for (int j = 0; j < dq.size(); ++j) {
    const LuGreJointStep<S> step = lugre_joint_step(p, j, state.z[j], dq[j], abs_gravity[j], dt);
    state.z[j] = step.z;
    tau[j] = step.torque;
  }
  return tau;
}

/// Deflection the bristles settle at when sliding steadily at q̇: z = sgn(q̇)·g(q̇)/σ0.
template <typename S, int N>
JointVector<S, N> lugre_steady_deflection(const LuGreParameters<S, N>& p,
                                          const JointVector<S, N>& dq,
                                          const JointVector<S, N>& abs_gravity) {
  JointVector<S, N> z;
  z.resize(dq.size());
  for (int j = 0; j < dq.size(); ++j) {
    const S level = stribeck_level(p.stribeck, j, dq[j], abs_gravity[j]);
    const S sign = dq[j] > S(0) ? S(1) : (dq[j] < S(0) ? S(-1) : S(0));
    z[j] = sign * level / p.bristle_stiffness[j];
  }
  return z;
}

}  // namespace tpf
