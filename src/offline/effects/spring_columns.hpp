// Candidate: a joint spring or cable torque k·q (the run-time JointSpring).
#pragma once

#include "offline/effects/added_effect_columns.hpp"
#include "offline/effects/design_context.hpp"
#include "tpf/effects/joint_spring.hpp"

namespace tpf::offline {

struct SpringColumns : AddedEffectColumns<JointSpring> {
  static constexpr bool kExtrapolatesInQ = true;  ///< k·q grows without bound outside the range
  static bool offered(const DesignContext&, int joint) { return joint >= 0; }
  static GroupSpec group(const DesignContext&, int joint) {
    return {"joint spring or cable torque (k·q), " + joint_title(joint),
            {"k" + joint_suffix(joint)}};
  }
};

}  // namespace tpf::offline
