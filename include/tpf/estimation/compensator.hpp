// The friction compensator's interface: what the estimator feeds the TCN and reads back.
#pragma once

#include <Eigen/Core>
#include <concepts>

#include "tpf/common/types.hpp"

namespace tpf {

/// A streaming friction compensator for N joints: `step(x)` takes the 4N inputs of
/// compensator_input and returns the N predicted friction residuals τ_TCN (the effort unit of the
/// residual it was trained on); `reset(x)` prewarms its history with a steady input.
/// tpf::Tcn<S, 4N, Hidden, Levels, Kernel, N> satisfies it, and so does ZeroCompensator.
template <typename C, typename S, int N>
concept FrictionCompensator = requires(C c, const Eigen::Matrix<S, 4 * N, 1>& x) {
  { c.step(x) } -> std::convertible_to<Eigen::Matrix<S, N, 1>>;
  c.reset(x);
};

/// The compensator input x = [q; q̇; q̈; τ̂_fric,s] (4N: rad, rad/s, rad/s², effort unit), with
/// τ̂_fric,s = StaticFrictionTracker::friction_estimate() (0 on moving joints). The trainer builds
/// its training inputs with this same function.
template <typename S, int N>
Eigen::Matrix<S, 4 * N, 1> compensator_input(const JointVector<S, N>& q,
                                             const JointVector<S, N>& dq,
                                             const JointVector<S, N>& ddq,
                                             const JointVector<S, N>& static_friction) noexcept {
  Eigen::Matrix<S, 4 * N, 1> x;
  x << q, dq, ddq, static_friction;
  return x;
}

/// No compensation: τ_TCN = 0 (the fused estimator then equals the nominal one). For tests and
/// for running before trained weights exist.
template <typename S, int N>
struct ZeroCompensator {
  using Output = Eigen::Matrix<S, N, 1>;
  const Output& step(const Eigen::Matrix<S, 4 * N, 1>&) noexcept { return zero; }
  void reset(const Eigen::Matrix<S, 4 * N, 1>&) noexcept {}
  Output zero = Output::Zero();
};

}  // namespace tpf
