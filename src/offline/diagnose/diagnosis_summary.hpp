// diagnose's verdict at a glance: one row per effect it claimed, checked against the robot
// file or came close to claiming, each with a reason of a few words (the first screen's table).
#pragma once

#include "offline/diagnose/diagnose.hpp"
#include "offline/report/html_report.hpp"

namespace tpf::offline {

/// Rows: every claim (written to the parameter file or not, and why), the payload checked against
/// the robot file's inertias when it would remove at least `options.min_improvement`, then the
/// candidates not claimed that removed the most (at least half of min_improvement in some
/// round), at most `max_rejected` of them. Columns: effect, joint, held-out gain (share of the
/// held-out residual sum of squares removed), written, why (≤ 12 words).
Table diagnosis_summary_table(const EffectDiagnosis& diagnosis, const DiagnoseOptions& options,
                              int max_rejected = 3);

}  // namespace tpf::offline
