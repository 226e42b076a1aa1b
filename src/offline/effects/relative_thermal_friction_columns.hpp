// Candidate: the viscous friction of every joint changing with temperature by one shared relative
// coefficient, b_j·(1 + β(T_j − T_ref)): column (T_j − T_ref)·b_j·q̇_j with b_j the declared fit's
// viscous coefficient (ThermalFriction: not evaluated at run time, it has no temperature input).
#pragma once

#include "offline/effects/design_context.hpp"
#include "offline/effects/offline_only_columns.hpp"
#include "offline/effects/sample_row.hpp"
#include "tpf/effects/thermal_friction.hpp"

namespace tpf::offline {

struct RelativeThermalFrictionColumns : OfflineOnlyColumns {
  static constexpr std::string_view key = ThermalFriction::key;

  static bool offered(const DesignContext& c, int joint) {
    return joint < 0 && c.has_temperature && c.inputs.viscous.size() == c.joints && c.joints > 1;
  }
  static GroupSpec group(const DesignContext&, int) {
    return {
        "temperature-dependent friction, every joint (one relative change of the viscous "
        "friction per °C)",
        {"beta_v"}};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    out[0] = (row.samples.temperature(row.k, joint) - row.inputs.reference_temperature) *
             row.motion.dq[joint] * row.inputs.viscous[joint];
  }
};

}  // namespace tpf::offline
