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

  JointVector<S, N> offset = zero_or_empty<JointVector<S, N>>();  ///< c [N·m]; 0 = absent

  /// φ_j = 1.
  static void basis(const EffectInput<S, N>&, int, S* columns) noexcept { columns[0] = S(1); }
  void coefficients(int joint, S* out) const noexcept { out[0] = offset[joint]; }
  void set_coefficients(int joint, const S* in) noexcept { offset[joint] = in[0]; }
  /// Sizes the parameters for n joints, all zero (absent).
  void resize(int n) { offset = JointVector<S, N>::Zero(n); }
  /// The same effect of another joint-count type (the counts must agree).
  template <int From>
  void assign(const JointOffset<S, From>& from) {
    offset = from.offset;
  }
  int columns() const noexcept { return kColumns; }
  bool present() const noexcept { return (offset.array() != S(0)).any(); }
  void add_torque(const EffectInput<S, N>& x, JointVector<S, N>& tau) const
      noexcept(N != Eigen::Dynamic) {
    add_linear_effect_torque(*this, x, tau);
  }

  /// Parameter file, "added_effects": "offset": [c_1 … c_N] (optional). Files of the 4-DoF demo
  /// name it "spring_offset" (the spring's k·q + offset); both are read and add up.
  template <typename Fields>
  void read(Fields& added) {
    added.joint_vector("offset", offset, false);
    JointVector<double, N> spring_offset = JointVector<double, N>::Zero(offset.size());
    added.joint_vector("spring_offset", spring_offset, false);
    offset += spring_offset.template cast<S>();
  }
  template <typename Json>
  void write(Json& added) const {
    added["offset"] = joint_values<S, N>(offset);
  }
};

}  // namespace tpf
