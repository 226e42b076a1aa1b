// A compensator wrapper that keeps the last input it was given: the training features are read
// from the run-time estimator itself, so training and use cannot drift apart.
#pragma once

#include <Eigen/Core>

#include "tpf/estimation/compensator.hpp"

namespace tpf::offline {

/// Forwards step/reset to `Inner` (a Tcn, PerJointTcn or ZeroCompensator) and remembers the last
/// input x = compensator_input(q, q̇, q̈, τ̂_fric,s, τ_fric,nom) that the estimator built.
/// Allocation-free step; at Eigen::Dynamic the estimator sizes it (resize) at construction.
template <typename Inner, typename S, int N>
requires FrictionCompensator<Inner, S, N>
struct RecordingCompensator {
  using Input = CompensatorInput<S, N>;
  int receptive_field() const noexcept { return compensator_memory_of(inner); }

  decltype(auto) step(const Input& x) noexcept {
    last_input = x;
    return inner.step(x);
  }
  void reset(const Input& x) noexcept { inner.reset(x); }
  /// Sizes the recorded input (5·joints) and the inner compensator (resize_compensator).
  void resize(int joints) {
    last_input = Input::Zero(kCompensatorInputsPerJoint * joints);
    resize_compensator(inner, joints);
  }

  Inner inner{};
  Input last_input = zero_or_empty<Input>();
};

}  // namespace tpf::offline
