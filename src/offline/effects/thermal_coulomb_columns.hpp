// Candidate: the Coulomb (sliding) friction of a joint changing with its temperature,
// (T_j − T_ref)·s, s = sgn(q̇_j) when moving else 0: ThermalFrictionColumns' viscous column's
// Coulomb counterpart (not evaluated at run time, it has no temperature input). Read by the
// measured study beside ThermalFrictionColumns (SensorCandidateColumns); not in CandidateColumns,
// whose thermal candidate is the viscous one.
#pragma once

#include <string_view>

#include "offline/effects/design_context.hpp"
#include "offline/effects/offline_only_columns.hpp"
#include "offline/effects/sample_row.hpp"

namespace tpf::offline {

struct ThermalCoulombColumns : OfflineOnlyColumns {
  static constexpr std::string_view key = "thermal_coulomb";

  static bool offered(const DesignContext& c, int joint) { return joint >= 0 && c.has_temperature; }
  static GroupSpec group(const DesignContext&, int joint) {
    return {"temperature-dependent Coulomb friction, " + joint_title(joint),
            {"beta_c" + joint_suffix(joint)}};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    out[0] = (row.samples.temperature(row.k, joint) - row.inputs.reference_temperature) *
             row.direction[joint];
  }
};

}  // namespace tpf::offline
