// A constant torque on each joint, τ_j += c_j (N·m): an added effect.
#pragma once

#include <string_view>

#include "tpf/effects/effect_fields.hpp"
#include "tpf/effects/linear_effect.hpp"

namespace tpf {

template <typename S, int N>
struct JointOffset {
  static constexpr std::string_view key = "offset";  ///< diagnose's name of the effect
  static constexpr int kColumns = 1;                 ///< basis functions per joint

  JointVector<S, N> offset = JointVector<S, N>::Zero();  ///< c [N·m]; 0 = absent

  /// φ_j = 1.
  static void basis(const EffectInput<S, N>&, int, S* columns) noexcept { columns[0] = S(1); }
  void coefficients(int joint, S* out) const noexcept { out[0] = offset[joint]; }
  void set_coefficients(int joint, const S* in) noexcept { offset[joint] = in[0]; }
  bool present() const noexcept { return (offset.array() != S(0)).any(); }
  void add_torque(const EffectInput<S, N>& x, JointVector<S, N>& tau) const noexcept {
    add_linear_effect_torque(*this, x, tau);
  }

  /// Parameter file, "added_effects": "offset": [c_1 … c_N] (optional). Files of the 4-DoF demo
  /// name it "spring_offset" (the spring's k·q + offset); both are read and add up.
  template <typename Fields>
  void read(Fields& added) {
    added.template joint_vector<N>("offset", offset, false);
    JointVector<double, N> spring_offset = JointVector<double, N>::Zero();
    added.template joint_vector<N>("spring_offset", spring_offset, false);
    offset += spring_offset.template cast<S>();
  }
  template <typename Json>
  void write(Json& added) const {
    added["offset"] = joint_values<S, N>(offset);
  }
};

}  // namespace tpf
