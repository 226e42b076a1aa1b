// Torque on a joint from the other joints' motion, τ_j += Σ_k≠j (C_v,jk·q̇_k + C_a,jk·q̈_k)
// (C_v in N·m·s/rad, C_a in N·m·s²/rad): an added effect.
#pragma once

#include <string_view>

#include "tpf/effects/effect_fields.hpp"
#include "tpf/effects/linear_effect.hpp"

namespace tpf {

template <typename S, int N>
struct MotionCoupling {
  static constexpr std::string_view key = "coupling";  ///< diagnose's name of the effect
  /// Basis functions per joint (Eigen::Dynamic at a run-time joint count: see columns()).
  static constexpr int kColumns = N == Eigen::Dynamic ? Eigen::Dynamic : 2 * (N - 1);

  JointMatrix<S, N> velocity = zero_or_empty<JointMatrix<S, N>>();      ///< C_v, zero diagonal
  JointMatrix<S, N> acceleration = zero_or_empty<JointMatrix<S, N>>();  ///< C_a, zero diagonal

  /// Sizes the parameters for n joints, all zero (absent).
  void resize(int n) { velocity = acceleration = JointMatrix<S, N>::Zero(n, n); }
  /// The same effect of another joint-count type (the counts must agree).
  template <int From>
  void assign(const MotionCoupling<S, From>& from) {
    velocity = from.velocity;
    acceleration = from.acceleration;
  }
  /// Basis functions per joint: 2·(n − 1).
  int columns() const noexcept { return 2 * (static_cast<int>(velocity.rows()) - 1); }

  /// φ_j = q̇_k, q̈_k for every k ≠ j, in that order.
  static void basis(const EffectInput<S, N>& x, int joint, S* columns) noexcept {
    for (int k = 0; k < static_cast<int>(x.dq.size()); ++k)
      if (k != joint) {
        *columns++ = x.dq[k];
        *columns++ = x.ddq[k];
      }
  }
  void coefficients(int joint, S* out) const noexcept {
    for (int k = 0; k < velocity.rows(); ++k)
      if (k != joint) {
        *out++ = velocity(joint, k);
        *out++ = acceleration(joint, k);
      }
  }
  void set_coefficients(int joint, const S* in) noexcept {
    for (int k = 0; k < velocity.rows(); ++k)
      if (k != joint) {
        velocity(joint, k) = *in++;
        acceleration(joint, k) = *in++;
      }
  }
  bool present() const noexcept {
    return (velocity.array() != S(0)).any() || (acceleration.array() != S(0)).any();
  }
  void add_torque(const EffectInput<S, N>& x, JointVector<S, N>& tau) const
      noexcept(N != Eigen::Dynamic) {
    add_linear_effect_torque(*this, x, tau);
  }

  /// Parameter file, "added_effects": "coupling_velocity", "coupling_acceleration": N rows of N
  /// (optional; the diagonal must be zero, a joint's own motion is the rigid body's).
  template <typename Fields>
  void read(Fields& added) {
    added.joint_matrix("coupling_velocity", velocity);
    added.joint_matrix("coupling_acceleration", acceleration);
    for (int j = 0; j < velocity.rows(); ++j)
      if (velocity(j, j) != S(0) || acceleration(j, j) != S(0))
        added.fail(velocity(j, j) != S(0) ? "coupling_velocity" : "coupling_acceleration",
                   "the diagonal must be zero (a joint's own motion is the rigid body's)");
  }
  template <typename Json>
  void write(Json& added) const {
    added["coupling_velocity"] = joint_rows<S, N>(velocity);
    added["coupling_acceleration"] = joint_rows<S, N>(acceleration);
  }
};

}  // namespace tpf
