// Candidate: viscous friction of a joint changing with its temperature, (T_j − T_ref)·q̇_j
// (ThermalFriction: not evaluated at run time, it has no temperature input).
#pragma once

#include "offline/effects/design_context.hpp"
#include "offline/effects/offline_only_columns.hpp"
#include "offline/effects/sample_row.hpp"
#include "tpf/effects/thermal_friction.hpp"

namespace tpf::offline {

struct ThermalFrictionColumns : OfflineOnlyColumns {
  static constexpr std::string_view key = ThermalFriction::key;

  static bool offered(const DesignContext& c, int joint) { return joint >= 0 && c.has_temperature; }
  static GroupSpec group(const DesignContext&, int joint) {
    return {"temperature-dependent friction, " + joint_title(joint),
            {"beta_v" + joint_suffix(joint)}};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    out[0] = (row.samples.temperature(row.k, joint) - row.inputs.reference_temperature) *
             row.motion.dq[joint];
  }
};

}  // namespace tpf::offline
