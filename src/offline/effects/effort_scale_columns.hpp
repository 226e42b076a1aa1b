// Candidate: the joint's effort scaled, its column the effort itself (K_t·i): a torque-constant
// error, K_t·(1 − c) for the coefficient c. Only where the effort is not what is fitted: the
// measured study fits K_t·i − d − τ_sensor (SensorCandidateColumns); in diagnose, which fits the
// effort, the column would be its own target, so it is not in CandidateColumns.
#pragma once

#include <string_view>

#include "offline/effects/design_context.hpp"
#include "offline/effects/offline_only_columns.hpp"
#include "offline/effects/sample_row.hpp"

namespace tpf::offline {

struct EffortScaleColumns : OfflineOnlyColumns {
  static constexpr std::string_view key = "effort_scale";

  static bool offered(const DesignContext&, int joint) { return joint >= 0; }
  static GroupSpec group(const DesignContext&, int joint) {
    return {"torque constant error (effort scaled), " + joint_title(joint),
            {"kt_scale" + joint_suffix(joint)}};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    out[0] = row.samples.effort(row.k, joint);
  }
};

}  // namespace tpf::offline
