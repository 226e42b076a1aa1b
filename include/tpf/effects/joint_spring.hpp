// A spring or cable torque on each joint, τ_j += k_j·q_j (k in N·m/rad): an added effect.
#pragma once

#include <string_view>

#include "tpf/effects/effect_fields.hpp"
#include "tpf/effects/linear_effect.hpp"

namespace tpf {

template <typename S, int N>
struct JointSpring {
  static constexpr std::string_view key = "spring";  ///< diagnose's name of the effect
  static constexpr int kColumns = 1;                 ///< basis functions per joint

  JointVector<S, N> stiffness = zero_or_empty<JointVector<S, N>>();  ///< k [N·m/rad]; 0 = absent

  /// φ_j = q_j.
  static void basis(const EffectInput<S, N>& x, int joint, S* columns) noexcept {
    columns[0] = x.q[joint];
  }
  void coefficients(int joint, S* out) const noexcept { out[0] = stiffness[joint]; }
  void set_coefficients(int joint, const S* in) noexcept { stiffness[joint] = in[0]; }
  /// Sizes the parameters for n joints, all zero (absent).
  void resize(int n) { stiffness = JointVector<S, N>::Zero(n); }
  /// The same effect of another joint-count type (the counts must agree).
  template <int From>
  void assign(const JointSpring<S, From>& from) {
    stiffness = from.stiffness;
  }
  int columns() const noexcept { return kColumns; }
  bool present() const noexcept { return (stiffness.array() != S(0)).any(); }
  void add_torque(const EffectInput<S, N>& x, JointVector<S, N>& tau) const
      noexcept(N != Eigen::Dynamic) {
    add_linear_effect_torque(*this, x, tau);
  }

  /// Parameter file, "added_effects": "spring_stiffness": [k_1 … k_N] (optional).
  template <typename Fields>
  void read(Fields& added) {
    added.joint_vector("spring_stiffness", stiffness, false);
  }
  template <typename Json>
  void write(Json& added) const {
    added["spring_stiffness"] = joint_values<S, N>(stiffness);
  }
};

}  // namespace tpf
