// Candidate: a delay between effort and motion, d(rigid-body prediction_j)/dt (the coefficient is
// the effort's lead over the motion, s), per joint and for every joint at once (one shared lead)
// (EffortDelay: not evaluated at run time, it keeps no past samples).
#pragma once

#include <cmath>

#include "offline/effects/design_context.hpp"
#include "offline/effects/offline_only_columns.hpp"
#include "offline/effects/sample_row.hpp"
#include "tpf/effects/effort_delay.hpp"

namespace tpf::offline {

struct DelayColumns : OfflineOnlyColumns {
  static constexpr std::string_view key = EffortDelay::key;

  static bool offered(const DesignContext& c, int joint) {
    return c.inputs.prediction_rate.cols() == c.joints && (joint >= 0 || c.joints > 1);
  }
  static GroupSpec group(const DesignContext&, int joint) {
    if (joint < 0) return {"delay between effort and motion, every joint (one lead)", {"lead_s"}};
    return {"delay between effort and motion, " + joint_title(joint),
            {"lead_s" + joint_suffix(joint)}};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    const double rate = row.inputs.prediction_rate(row.k, joint);
    out[0] = std::isfinite(rate) ? rate : 0.0;
  }
};

}  // namespace tpf::offline
