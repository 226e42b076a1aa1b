// Stribeck + viscous joint friction, with the load-dependent form and a smooth variant for fitting.
//
// Units: velocities in rad/s (output side), torques in N·m. Sign convention: τ_f is the friction
// torque the drive must overcome, i.e. it has the sign of q̇ and enters τ_meas = τ_dyn + τ_f + τ_res
// with a plus sign.
#pragma once

#include <cmath>

#include "tpf/common/types.hpp"

namespace tpf {

/// Per joint parameters of  τ_f(q̇) = [τ_c + α_c|G| + (τ_s − τ_c)·exp(−|q̇/q̇_s|^δ)]·sgn(q̇)
///                                     + (b + α_v|G|)·q̇ + a_c·|sgn(q̇)| + a_v·|q̇|
///                                     + Σ_k≠j (β_jk·sgn(q̇) + γ_jk·q̇)·|G_k|.
/// The load terms scale with |G_j(q)|, the gravity torque of the joint, a proxy for the load on
/// the transmission; α_c = α_v = 0 gives the plain Stribeck + viscous curve. The break-away
/// excess (τ_s − τ_c) is load-independent, so each load term is linear in its coefficient.
/// The direction asymmetry a_c, a_v makes the sliding level τ_c + a_c moving forward and
/// τ_c − a_c backward (viscous b ± a_v). The neighbour-load terms β, γ (zero diagonal) let joint
/// j's friction grow with the gravity load |G_k| of another joint k (a shared bearing or belt);
/// only the whole-arm form (JointVector abs_gravity) evaluates them.
///
/// At Eigen::Dynamic the vectors start empty: resize(n) gives n joints the defaults below.
template <typename S, int N>
struct StribeckParameters {
  using Vector = JointVector<S, N>;
  using Matrix = JointMatrix<S, N>;
  Vector coulomb = zero_or_empty<Vector>();                 ///< τ_c ≥ 0
  Vector static_friction = zero_or_empty<Vector>();         ///< τ_s ≥ 0 (break-away)
  Vector stribeck_velocity = constant_or_empty(S(1));       ///< q̇_s > 0, rad/s
  Vector stribeck_exponent = constant_or_empty(S(2));       ///< δ > 0
  Vector viscous = zero_or_empty<Vector>();                 ///< b ≥ 0, per rad/s
  Vector load_coulomb = zero_or_empty<Vector>();            ///< α_c ≥ 0, per unit |G|
  Vector load_viscous = zero_or_empty<Vector>();            ///< α_v ≥ 0, per unit |G|·rad/s
  Vector coulomb_asymmetry = zero_or_empty<Vector>();       ///< a_c, |a_c| ≤ τ_c
  Vector viscous_asymmetry = zero_or_empty<Vector>();       ///< a_v, per rad/s
  Matrix neighbour_load_coulomb = zero_or_empty<Matrix>();  ///< β, zero diagonal
  Matrix neighbour_load_viscous = zero_or_empty<Matrix>();  ///< γ, zero diagonal

  /// Sizes every coefficient for n joints with the defaults (no friction, q̇_s = 1, δ = 2).
  void resize(int n) {
    for (Vector* v : {&coulomb, &static_friction, &viscous, &load_coulomb, &load_viscous,
                      &coulomb_asymmetry, &viscous_asymmetry})
      *v = Vector::Zero(n);
    stribeck_velocity = Vector::Ones(n);
    stribeck_exponent = Vector::Constant(n, S(2));
    neighbour_load_coulomb = neighbour_load_viscous = Matrix::Zero(n, n);
  }

 private:
  static Vector constant_or_empty(S value) {
    if constexpr (N == Eigen::Dynamic)
      return Vector();
    else
      return Vector::Constant(value);
  }
};

/// The same parameters with joint count `To` (Eigen::Dynamic, or the count they have: tpf::Error
/// otherwise) and scalar `ToS`. Start-up code.
template <int To, typename ToS, typename S, int From>
StribeckParameters<ToS, To> joint_count_cast(const StribeckParameters<S, From>& from) {
  require_joint_count<To>(static_cast<int>(from.coulomb.size()), "the friction parameters");
  StribeckParameters<ToS, To> to;
  to.coulomb = from.coulomb.template cast<ToS>();
  to.static_friction = from.static_friction.template cast<ToS>();
  to.stribeck_velocity = from.stribeck_velocity.template cast<ToS>();
  to.stribeck_exponent = from.stribeck_exponent.template cast<ToS>();
  to.viscous = from.viscous.template cast<ToS>();
  to.load_coulomb = from.load_coulomb.template cast<ToS>();
  to.load_viscous = from.load_viscous.template cast<ToS>();
  to.coulomb_asymmetry = from.coulomb_asymmetry.template cast<ToS>();
  to.viscous_asymmetry = from.viscous_asymmetry.template cast<ToS>();
  to.neighbour_load_coulomb = from.neighbour_load_coulomb.template cast<ToS>();
  to.neighbour_load_viscous = from.neighbour_load_viscous.template cast<ToS>();
  return to;
}

/// True when some neighbour-load coefficient is non-zero (G(q) of every joint is then needed).
template <typename S, int N>
bool has_neighbour_load(const StribeckParameters<S, N>& p) {
  return (p.neighbour_load_coulomb.array() != S(0)).any() ||
         (p.neighbour_load_viscous.array() != S(0)).any();
}

/// Default smoothing velocity ε of the smooth form, rad/s: ten steps of the PH54 velocity
/// resolution (0.01 rev/min = 1.05e-3 rad/s), so measurement noise at rest does not flip the sign.
template <typename S>
inline constexpr S kDefaultFrictionSmoothing = S(0.01);

/// Magnitude of the sliding friction of joint j without the viscous part:
/// g_j(q̇) = τ_c + α_c|G| + (τ_s − τ_c)·exp(−|q̇/q̇_s|^δ).
template <typename S, int N>
S stribeck_level(const StribeckParameters<S, N>& p, int j, S dq, S abs_gravity) {
  using std::abs, std::exp, std::pow;
  const S ratio = abs(dq / p.stribeck_velocity[j]);
  return p.coulomb[j] + p.load_coulomb[j] * abs_gravity +
         (p.static_friction[j] - p.coulomb[j]) * exp(-pow(ratio, p.stribeck_exponent[j]));
}

/// Viscous coefficient of joint j under load: b + α_v|G|.
template <typename S, int N>
S viscous_coefficient(const StribeckParameters<S, N>& p, int j, S abs_gravity) {
  return p.viscous[j] + p.load_viscous[j] * abs_gravity;
}

/// Friction of joint j without the neighbour-load terms: τ_f = g_j(q̇)·sgn(q̇) + (b + α_v|G|)·q̇
/// + a_c·|sgn(q̇)| + a_v·|q̇|, with sgn(0) = 0 (g_j, its pow and exp, is then not evaluated).
template <typename S, int N>
S stribeck_friction(const StribeckParameters<S, N>& p, int j, S dq, S abs_gravity = S(0)) {
  using std::abs;
  const S sign = dq > S(0) ? S(1) : (dq < S(0) ? S(-1) : S(0));
  const S level = sign != S(0) ? stribeck_level(p, j, dq, abs_gravity) : S(0);
  return level * sign + viscous_coefficient(p, j, abs_gravity) * dq +
         p.coulomb_asymmetry[j] * abs(sign) + p.viscous_asymmetry[j] * abs(dq);
}

/// Neighbour-load part of joint j's friction: Σ_k≠j (β_jk·sgn(q̇_j) + γ_jk·q̇_j)·|G_k|.
template <typename S, int N>
S neighbour_load_friction(const StribeckParameters<S, N>& p, int j, S dq,
                          const JointVector<S, N>& abs_gravity) {
  const S sign = dq > S(0) ? S(1) : (dq < S(0) ? S(-1) : S(0));
  return p.neighbour_load_coulomb.row(j).dot(abs_gravity) * sign +
         p.neighbour_load_viscous.row(j).dot(abs_gravity) * dq;
}

/// Load-dependent friction of every joint, |G_j(q)| passed in `abs_gravity`: the per-joint
/// form above plus the neighbour-load terms (see StribeckParameters).
template <typename S, int N>
JointVector<S, N> stribeck_friction(const StribeckParameters<S, N>& p, const JointVector<S, N>& dq,
                                    const JointVector<S, N>& abs_gravity) {
  JointVector<S, N> tau;
  tau.resize(dq.size());
  for (int j = 0; j < dq.size(); ++j)
    tau[j] = stribeck_friction(p, j, dq[j], abs_gravity[j]) +
             neighbour_load_friction(p, j, dq[j], abs_gravity);
  return tau;
}

/// Load-dependent friction of every joint without the neighbour-load terms (equal to the whole-arm
/// form above when every β, γ is zero, where those terms add zeros).
template <typename S, int N>
JointVector<S, N> own_load_stribeck_friction(const StribeckParameters<S, N>& p,
                                             const JointVector<S, N>& dq,
                                             const JointVector<S, N>& abs_gravity) {
  JointVector<S, N> tau;
  tau.resize(dq.size());
  for (int j = 0; j < dq.size(); ++j)
    tau[j] = stribeck_friction(p, j, dq[j], abs_gravity[j]);
  return tau;
}

/// Friction of every joint, no load: τ_f,j = g_j(q̇_j)·sgn(q̇_j) + b_j·q̇_j (+ the direction
/// asymmetry), i.e. |G| = 0.
template <typename S, int N>
JointVector<S, N> stribeck_friction(const StribeckParameters<S, N>& p,
                                    const JointVector<S, N>& dq) {
  return own_load_stribeck_friction(p, dq, JointVector<S, N>::Zero(dq.size()).eval());
}

/// Smooth form for gradient-based fitting: sgn(q̇) is replaced by tanh(q̇/ε), which makes τ_f
/// continuous and differentiable at q̇ = 0 (τ_f(0) = 0) and equal to the sharp form within a
/// factor tanh(|q̇|/ε) ≥ 0.995 once |q̇| ≥ 3ε. The symmetric curve only: the direction
/// asymmetry and the neighbour-load terms are not part of it.
template <typename S, int N>
JointVector<S, N> smooth_stribeck_friction(const StribeckParameters<S, N>& p,
                                           const JointVector<S, N>& dq,
                                           const JointVector<S, N>& abs_gravity,
                                           S epsilon = kDefaultFrictionSmoothing<S>) {
  using std::tanh;
  JointVector<S, N> tau;
  tau.resize(dq.size());
  for (int j = 0; j < dq.size(); ++j) {
    tau[j] = stribeck_level(p, j, dq[j], abs_gravity[j]) * tanh(dq[j] / epsilon) +
             viscous_coefficient(p, j, abs_gravity[j]) * dq[j];
  }
  return tau;
}

}  // namespace tpf
