// Candidate: ripple periodic in the joint (output) angle, n periods per revolution of q (the
// run-time PositionRipple, output side).
#pragma once

#include <cstdio>

#include "offline/effects/design_context.hpp"
#include "offline/effects/ripple_columns.hpp"

namespace tpf::offline {

struct OutputRippleColumns : RippleColumns<false> {
  static constexpr std::string_view key = "ripple";
  static GroupSpec group(const DesignContext& c, int joint) {
    char title[96];
    std::snprintf(title, sizeof title, "position ripple, %s (%g periods/rev of q)",
                  joint_title(joint).c_str(), cycles(c.inputs, joint));
    const std::string n = joint_suffix(joint);
    return {title, {"ripple_sin" + n, "ripple_cos" + n}, -1, judged_beside()};
  }
};

}  // namespace tpf::offline
