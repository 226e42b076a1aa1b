// Candidate: a constant offset of a joint's effort (the run-time JointOffset).
#pragma once

#include "offline/effects/added_effect_columns.hpp"
#include "offline/effects/design_context.hpp"
#include "tpf/effects/joint_offset.hpp"

namespace tpf::offline {

struct OffsetColumns : AddedEffectColumns<JointOffset> {
  static bool offered(const DesignContext&, int joint) { return joint >= 0; }
  static GroupSpec group(const DesignContext&, int joint) {
    return {"constant offset, " + joint_title(joint), {"offset" + joint_suffix(joint)}};
  }
};

}  // namespace tpf::offline
