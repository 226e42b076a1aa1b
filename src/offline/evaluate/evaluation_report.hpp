// The evaluation as a readable page (HTML, labelled SIMULATED for twin logs) and a terminal table.
#pragma once

#include <string>

#include "offline/evaluate/evaluation.hpp"
#include "offline/report/html_report.hpp"

namespace tpf::offline {

/// The report page: Table I with the targets, dead bands, detection, force error, teaching, and
/// the plots (error distributions, a joint's residual around motion onsets with both models, the
/// teaching trace). `simulated` adds the SIMULATED banner; `notes` are listed under the title.
HtmlReport evaluation_report(const Evaluation& evaluation, bool simulated,
                             const std::vector<std::string>& notes);

/// Table I pooled over joints, one row per state: RMSE nominal → with the TCN, the change and the
/// paper's goal for that state (static ≤ −90 %, static-to-kinetic ≤ −60 %) met or not.
Table table_one_summary(const Evaluation& evaluation);

/// The headline: Table I pooled over joints and the targets, as fixed-width text, labelled
/// SIMULATED or MEASURED and with the logs' effort unit.
std::string evaluation_headline(const Evaluation& evaluation, bool simulated);

}  // namespace tpf::offline
