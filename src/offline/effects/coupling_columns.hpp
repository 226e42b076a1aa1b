// Candidate: torque on a joint from the other joints' velocity and acceleration (the run-time
// MotionCoupling).
#pragma once

#include "offline/effects/added_effect_columns.hpp"
#include "offline/effects/design_context.hpp"
#include "tpf/effects/motion_coupling.hpp"

namespace tpf::offline {

struct CouplingColumns : AddedEffectColumns<MotionCoupling> {
  static bool offered(const DesignContext& c, int joint) { return joint >= 0 && c.joints > 1; }
  static GroupSpec group(const DesignContext& c, int joint) {
    GroupSpec spec{"coupling from other joints' motion, " + joint_title(joint), {}};
    const std::string n = joint_suffix(joint);
    for (int k = 0; k < c.joints; ++k)
      if (k != joint) {
        spec.column_names.push_back("cv" + n + "_" + joint_suffix(k));
        spec.column_names.push_back("ca" + n + "_" + joint_suffix(k));
      }
    return spec;
  }
};

}  // namespace tpf::offline
