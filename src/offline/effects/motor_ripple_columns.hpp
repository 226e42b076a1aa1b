// Candidate: ripple periodic in the motor angle G·q, n periods per motor revolution (the run-time
// PositionRipple, motor side).
#pragma once

#include <cstdio>

#include "offline/effects/design_context.hpp"
#include "offline/effects/ripple_columns.hpp"

namespace tpf::offline {

struct MotorRippleColumns : RippleColumns<true> {
  static constexpr std::string_view key = "ripple_motor";
  static GroupSpec group(const DesignContext& c, int joint) {
    char title[96];
    std::snprintf(title, sizeof title, "motor-angle ripple, %s (%g periods/motor rev)",
                  joint_title(joint).c_str(), cycles(c.inputs, joint));
    const std::string n = joint_suffix(joint);
    return {title, {"motor_sin" + n, "motor_cos" + n}, -1, judged_beside()};
  }
};

}  // namespace tpf::offline
