// Causal joint acceleration from joint velocity: a second-order filtered derivative.
#pragma once

#include <cmath>
#include <numbers>

#include "tpf/common/types.hpp"

namespace tpf {

/// q̈ estimated from q̇ by the filtered differentiator
///   Q̈(s) = s·ω²/(s² + 2ζωs + ω²) · Q̇(s),   ω = 2π·f_c,
/// in state form v̇ = a, ȧ = ω²(q̇ − v) − 2ζω·a (v a smoothed velocity, a the acceleration), advanced
/// by backward Euler with each sample's own period h: [v; a]⁺ = (I − hA)⁻¹([v; a] + hB·q̇). Backward
/// Euler is stable for any h, so a dropped cycle cannot make it diverge. Group delay at low
/// frequency ≈ 2ζ/ω (+ h/2·… of the discretisation); f_c = 20 Hz, ζ = 0.8 gives ≈ 13 ms.
/// Allocation-free after construction, which sizes it for `joints` joints at Eigen::Dynamic.
template <typename S, int N>
class AccelerationFilter {
 public:
  explicit AccelerationFilter(S cutoff_hz = S(20), S damping = S(0.8),
                              int joints = N) noexcept(N != Eigen::Dynamic)
      : omega_(S(2) * std::numbers::pi_v<S> * cutoff_hz), zeta_(damping) {
    if constexpr (N == Eigen::Dynamic) velocity_ = acceleration_ = JointVector<S, N>::Zero(joints);
    (void)joints;
  }

  /// Steady start at velocity q̇ (acceleration 0).
  void reset(const JointVector<S, N>& dq) noexcept {
    velocity_ = dq;
    acceleration_.setZero();
  }

  /// Advances by q̇ sampled h > 0 seconds after the previous sample; returns q̈ [rad/s²].
  const JointVector<S, N>& update(const JointVector<S, N>& dq, S h) noexcept {
    // (I − hA) = [[1, −h], [hω², 1 + 2hζω]], right side [v + 0; a + hω²·q̇].
    const S w2 = omega_ * omega_;
    const S d = S(1) + S(2) * h * zeta_ * omega_;
    const S inverse_det = S(1) / (d + h * h * w2);
    for (int j = 0; j < velocity_.size(); ++j) {
      const S r1 = velocity_[j];
      const S r2 = acceleration_[j] + h * w2 * dq[j];
      velocity_[j] = (d * r1 + h * r2) * inverse_det;
      acceleration_[j] = (r2 - h * w2 * r1) * inverse_det;
    }
    return acceleration_;
  }

  const JointVector<S, N>& value() const noexcept { return acceleration_; }

 private:
  S omega_;
  S zeta_;
  JointVector<S, N> velocity_ = zero_or_empty<JointVector<S, N>>();
  JointVector<S, N> acceleration_ = zero_or_empty<JointVector<S, N>>();
};

}  // namespace tpf
