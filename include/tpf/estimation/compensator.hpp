// The friction compensator's interface: what the estimator feeds the TCN and reads back.
#pragma once

#include <Eigen/Core>
#include <concepts>

#include "tpf/common/types.hpp"

namespace tpf {

/// Inputs per joint of the compensator: q, q̇, q̈, τ̂_fric,s and τ_fric,nom (compensator_input).
inline constexpr int kCompensatorInputsPerJoint = 5;

/// The length of the compensator input of N joints: 5N, or Eigen::Dynamic.
template <int N>
inline constexpr int kCompensatorInputs =
    N == Eigen::Dynamic ? Eigen::Dynamic : kCompensatorInputsPerJoint* N;

/// The compensator input of N joints, x = [q; q̇; q̈; τ̂_fric,s; τ_fric,nom], 5N long.
template <typename S, int N>
using CompensatorInput = Eigen::Matrix<S, kCompensatorInputs<N>, 1>;

/// A streaming friction compensator for N joints: `step(x)` takes the 5N inputs of
/// compensator_input and returns the N predicted friction residuals τ_TCN [N·m]; `reset(x)`
/// prewarms its history with a steady input. tpf::Tcn<S, 5N, Hidden, Levels, Kernel, N> satisfies
/// it, and so does ZeroCompensator. A compensator of Eigen::Dynamic joints also has
/// resize(joints), which the estimator calls at construction (resize_compensator).
template <typename C, typename S, int N>
concept FrictionCompensator = requires(C c, const CompensatorInput<S, N>& x) {
  { c.step(x) } -> std::convertible_to<Eigen::Matrix<S, N, 1>>;
  c.reset(x);
};

/// The compensator input x = [q; q̇; q̈; τ̂_fric,s; τ_fric,nom] (5N: rad, rad/s, rad/s², N·m,
/// N·m), block c of N holding channel c of every joint, with
///   τ̂_fric,s  = StaticFrictionTracker::friction_estimate() (the held friction, 0 while moving);
///   τ_fric,nom = the nominal model's friction at q̇ as predict_effort evaluates it,
///                [τ_c + α_c|G| + (τ_s − τ_c)·exp(−|q̇/q̇_s|^δ)]·sgn(q̇) + (b + α_v|G|)·q̇.
/// τ_fric,nom is bounded and tells rest (sgn 0 = 0) from the first velocity quantum at full
/// Coulomb level, which the normalised q̇ cannot (docs/tcn-break-away.md). The trainer builds
/// its training inputs with this same function. Allocates the result at Eigen::Dynamic.
template <typename S, int N>
CompensatorInput<S, N> compensator_input(
    const JointVector<S, N>& q, const JointVector<S, N>& dq, const JointVector<S, N>& ddq,
    const JointVector<S, N>& static_friction,
    const JointVector<S, N>& nominal_friction) noexcept(N != Eigen::Dynamic) {
  CompensatorInput<S, N> x;
  x.resize(kCompensatorInputsPerJoint * q.size());
  x << q, dq, ddq, static_friction, nominal_friction;
  return x;
}

/// The same into x, already 5n long for n joints (allocation-free at Eigen::Dynamic too).
template <typename S, int N>
void compensator_input(const JointVector<S, N>& q, const JointVector<S, N>& dq,
                       const JointVector<S, N>& ddq, const JointVector<S, N>& static_friction,
                       const JointVector<S, N>& nominal_friction,
                       CompensatorInput<S, N>& x) noexcept {
  x << q, dq, ddq, static_friction, nominal_friction;
}

/// Sizes compensator c for `joints` joints where it has resize(joints) (one of Eigen::Dynamic
/// joints); nothing otherwise. Start-up code.
template <typename C>
void resize_compensator(C& c, int joints) {
  if constexpr (requires { c.resize(joints); }) c.resize(joints);
}

/// Cycles of input history a compensator's output depends on: its receptive field
/// (C::kReceptiveField, a TCN), 1 for a memoryless one.
template <typename C>
inline constexpr int compensator_memory = [] {
  if constexpr (requires { C::kReceptiveField; })
    return static_cast<int>(C::kReceptiveField);
  else
    return 1;
}();

/// The same for a compensator whose network is chosen at start-up (member receptive_field()).
template <typename C>
int compensator_memory_of(const C& c) noexcept {
  if constexpr (requires { c.receptive_field(); })
    return c.receptive_field();
  else
    return compensator_memory<C>;
}

/// No compensation: τ_TCN = 0 (the fused estimator then equals the nominal one). For tests and
/// for running before trained weights exist. At Eigen::Dynamic resize(joints) sizes its output.
template <typename S, int N>
struct ZeroCompensator {
  using Output = Eigen::Matrix<S, N, 1>;
  const Output& step(const CompensatorInput<S, N>&) noexcept { return zero; }
  void reset(const CompensatorInput<S, N>&) noexcept {}
  void resize(int joints) { zero = Output::Zero(joints); }
  Output zero = zero_or_empty<Output>();
};

}  // namespace tpf
