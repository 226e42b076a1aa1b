// Candidate: a delay between effort and motion, (p_j(t) − p_j(t − lag))/lag of the declared
// model's rigid-body prediction p over the lag searched on its residual (search_effort_lag; the
// coefficient is the effort's lead over the motion, s), per joint and for every joint at once (one
// shared lead) (EffortDelay: not evaluated at run time, it keeps no past samples).
#pragma once

#include <cmath>
#include <string>

#include "offline/effects/design_context.hpp"
#include "offline/effects/offline_only_columns.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/report/text_format.hpp"
#include "tpf/effects/effort_delay.hpp"

namespace tpf::offline {

struct DelayColumns : OfflineOnlyColumns {
  static constexpr std::string_view key = EffortDelay::key;

  static bool offered(const DesignContext& c, int joint) {
    return c.inputs.prediction_rate.cols() == c.joints && (joint >= 0 || c.joints > 1);
  }
  static GroupSpec group(const DesignContext& c, int joint) {
    std::string title = "delay between effort and motion, ";
    title += joint < 0 ? "every joint (one lead; " : joint_title(joint) + " (";
    title += format_sentence("difference over %.3g ms)", 1e3 * c.inputs.effort_lag_s);
    return {title, {joint < 0 ? "lead_s" : "lead_s" + joint_suffix(joint)}};
  }
  static void fill(const SampleRow& row, int joint, double* out) {
    const double rate = row.inputs.prediction_rate(row.k, joint);
    out[0] = std::isfinite(rate) ? rate : 0.0;
  }
};

}  // namespace tpf::offline
