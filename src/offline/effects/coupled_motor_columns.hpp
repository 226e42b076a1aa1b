// Candidate: a coupled motor the robot file does not declare. For an adjacent pair of joints
// (i, i + 1) whose motors are declared uncoupled, a motor turning with θ = a·q_i + b·q_{i+1}
// (CoupledMotorCandidate: the ratio fitted to the declared model's residual), whose friction and
// rotor act on the joints through Cᵀ: on joint i with the share a, on joint i + 1 with b,
//   [a; b]·s,  [a; b]·θ̇,  and [a; b]·θ̈ where the rigid body does not span it,
// s = sgn(θ̇) when |θ̇| ≥ the static velocity, else 0. One group per pair, acting on its two
// joints. Not written to the parameter file: a coupling is the robot file's (`coupled_to`).
#pragma once

#include <string>
#include <string_view>

#include "offline/effects/design_context.hpp"
#include "offline/effects/feature_group.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/written_model.hpp"
#include "offline/report/text_format.hpp"

namespace tpf::offline {

struct CoupledMotorColumns {
  static constexpr std::string_view key = "coupled_motor";
  static constexpr WrittenTo written_to = WrittenTo::kRobotFile;
  static constexpr bool kSharedGroupFirst = false;
  static constexpr int kCoulomb = 0, kViscous = 1, kArmature = 2;

  /// One group per fitted candidate (CandidateInputs::coupled_motors), none per joint.
  static int variants(const DesignContext& c) {
    return static_cast<int>(c.inputs.coupled_motors.size());
  }
  static GroupSpec group(const DesignContext& c, int variant) {
    const CoupledMotorCandidate& m = c.inputs.coupled_motors[static_cast<std::size_t>(variant)];
    const std::string own = joint_suffix(m.own()), other = joint_suffix(m.other());
    const double ratio = m.ratio();
    GroupSpec spec{"coupled motor: motor " + own + " rotates with q" + own +
                       (ratio < 0 ? " − " : " + ") + format_number(std::abs(ratio), 3) + "·q" +
                       other + ", joints " + joint_suffix(m.joint) + "–" +
                       joint_suffix(m.joint + 1),
                   {"fc_coupled" + own + "_" + other, "fv_coupled" + own + "_" + other}};
    if (m.armature) spec.column_names.push_back("Ia_coupled" + own + "_" + other);
    spec.joints = {m.joint, m.joint + 1};
    spec.dissipative = {kCoulomb, kViscous};
    return spec;
  }
  static void fill(const SampleRow& row, int joint, int variant, double* out) {
    const CoupledMotorCandidate& m = row.inputs.coupled_motors[static_cast<std::size_t>(variant)];
    const int i = m.joint;
    const double share = joint == i ? m.a : joint == i + 1 ? m.b : 0.0;
    const double rate = m.a * row.motion.dq[i] + m.b * row.motion.dq[i + 1];
    const double sign = std::abs(rate) >= m.static_velocity ? (rate > 0 ? 1.0 : -1.0) : 0.0;
    out[kCoulomb] = share * sign;
    out[kViscous] = share * rate;
    if (m.armature)
      out[kArmature] = share * (m.a * row.motion.ddq[i] + m.b * row.motion.ddq[i + 1]);
  }
  /// Reported, never written: the parameter file cannot couple motors.
  static void write(const double*, int, WrittenModel&) {}
  static void remove(int, NominalModelX&) {}
};

}  // namespace tpf::offline
