#include "offline/diagnose/diagnosis_report.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/diagnose/diagnosis_summary.hpp"
#include "offline/regimes/regime.hpp"
#include "offline/regimes/regime_stats.hpp"
#include "offline/report/bar_chart.hpp"
#include "offline/report/html_report.hpp"
#include "offline/report/line_plot.hpp"
#include "offline/report/scatter_plot.hpp"
#include "offline/report/text_format.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

const char* kRegimeNames[4] = {"static", "static-to-kinetic", "moving", "all"};

// Samples of the held-out blocks only, as (x, y) series; others NaN.
Series heldout_series(const JointSamples& s, const std::string& name, const Eigen::VectorXd& x,
                      const Eigen::VectorXd& y) {
  Series out{name, x, y, ""};
  for (Eigen::Index k = 0; k < y.size(); ++k)
    if (!s.heldout[k]) out.y[k] = std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace

std::string diagnosis_json(const EffectDiagnosis& d) {
  const int N = d.joints();
  // Fitted in N·m; reported in the log's unit (mA for a log of currents). Coefficients stay SI.
  const DriveUnits& u = d.samples.units;
  nlohmann::json j;
  j["format"] = "tpf-diagnosis";
  j["version"] = 1;
  j["source"] = d.samples.source;
  j["simulated"] = d.samples.simulated;
  j["effort_unit"] = u.name();
  j["heldout_method"] = d.heldout_method;
  const Identification::InertiaPrior& prior = d.inertia_prior;
  if (prior.judged_strength > 0 || prior.written_strength > 0)
    j["inertia_prior"] = {{"strength", prior.judged_strength},
                          {"written_strength", prior.written_strength},
                          {"min_mass_eigenvalue_without", prior.judged_min_eigenvalue},
                          {"choice", prior.choice}};
  nlohmann::json joints = nlohmann::json::array();
  for (int i = 0; i < N; ++i) {
    nlohmann::json joint;
    joint["joint"] = i + 1;
    joint["noise_floor"] = u.to_effort(i, d.noise_floor[i]);
    if (i < d.motion_noise.size() && std::isfinite(d.motion_noise[i]))
      joint["noise_in_motion"] = u.to_effort(i, d.motion_noise[i]);
    for (int r = 0; r < 4; ++r) {
      const ResidualSums& b = d.before[i][r];
      const ResidualSums& a = d.after[i][r];
      joint["heldout"][kRegimeNames[r]] = {
          {"count", b.count},
          {"rmse_before", u.to_effort(i, b.rmse())},
          {"std_before", u.to_effort(i, b.std())},
          {"rmse_after", u.to_effort(i, a.rmse())},
          {"std_after", u.to_effort(i, a.std())},
          {"rmse_change_percent", percent_change(b.rmse(), a.rmse())}};
    }
    joints.push_back(joint);
  }
  j["joints"] = joints;
  nlohmann::json trials = nlohmann::json::array();
  for (const CandidateTrial& t : d.trials)
    trials.push_back(
        {{"effect", t.key},
         {"title", t.title},
         {"joint", t.joint + 1},
         {"round", t.round},
         {"heldout_improvement_percent", 100 * t.improvement},
         {"bic_change", t.bic_change},
         {"standard_errors_from_zero", t.wald},
         {"share_outside_model", t.distinct_share},
         {"transfer_improvement_percent", std::isnan(t.transfer_improvement)
                                              ? nlohmann::json(nullptr)
                                              : nlohmann::json(100 * t.transfer_improvement)},
         {"transfer_file", t.transfer_file},
         {"extrapolates_in_q", t.extrapolates},
         {"outside_range_improvement_percent", std::isnan(t.outside_improvement)
                                                   ? nlohmann::json(nullptr)
                                                   : nlohmann::json(100 * t.outside_improvement)},
         {"outside_range_samples", t.outside_samples},
         {"outside_range_file", t.outside_file},
         {"stand_in_for", t.stand_in_for},
         {"selected", t.selected}});
  for (std::size_t i = 0; i < d.trials.size(); ++i)  // a group of several joints: each one's
    if (std::isfinite(d.trials[i].weakest_joint_improvement))
      trials[i]["weakest_joint_improvement_percent"] = 100 * d.trials[i].weakest_joint_improvement;
  for (std::size_t i = 0; i < d.trials.size(); ++i)
    if (d.trials[i].negative_friction) trials[i]["negative_friction"] = true;
  j["trials"] = trials;
  nlohmann::json selected = nlohmann::json::array();
  for (int g : d.selected)
    selected.push_back({{"effect", d.groups[g].key},
                        {"title", d.groups[g].title},
                        {"joint", d.groups[g].joint + 1}});
  j["selected"] = selected;
  nlohmann::json claims = nlohmann::json::array();
  for (const Claim& claim : d.claims) {
    nlohmann::json names = nlohmann::json::array();
    for (std::size_t i = 0; i < claim.groups.size(); ++i)
      names.push_back(
          {{"effect", d.groups[claim.groups[i]].key},
           {"joint", d.groups[claim.groups[i]].joint + 1},
           {"title", d.groups[claim.groups[i]].title},
           {"heldout_improvement_percent", std::isfinite(claim.improvements[i])
                                               ? nlohmann::json(100 * claim.improvements[i])
                                               : nlohmann::json(nullptr)}});
    claims.push_back({{"ambiguous", claim.ambiguous()},
                      {"candidates", names},
                      {"coefficients", claim.coefficients},
                      {"standard_errors", claim.standard_errors},
                      {"share_outside_model", claim.distinct_share},
                      {"written", claim.written}});
  }
  j["claims"] = claims;
  nlohmann::json written = nlohmann::json::array();
  for (int jt = 0; jt < N; ++jt) {
    nlohmann::json row;
    for (Regime r : {Regime::Static, Regime::StaticToKinetic, Regime::Moving})
      row[std::string(regime_name(r))] = {{"before", u.to_effort(jt, d.written_before[jt][r].rmse)},
                                          {"after", u.to_effort(jt, d.written_after[jt][r].rmse)}};
    written.push_back(row);
  }
  j["written_model_heldout_rmse"] = written;
  const CadPayloadCheck& c = d.cad_payload;
  nlohmann::json payload_alternatives = nlohmann::json::array();
  for (int g : c.ambiguous_with)
    payload_alternatives.push_back(d.groups[g].title);
  j["payload_against_robot_file"] = {{"claimed", c.claimed},
                                     {"heldout_improvement_percent", 100 * c.improvement},
                                     {"bic_change", c.bic_change},
                                     {"mass_kg", c.mass},
                                     {"mass_standard_error_kg", c.mass_standard_error},
                                     {"centre_m", {c.centre.x(), c.centre.y(), c.centre.z()}},
                                     {"ambiguous_with", payload_alternatives},
                                     {"transfer_improvement_percent", 100 * c.transfer_improvement},
                                     {"transfer_file", c.transfer_file}};
  j["findings"] = d.findings;
  j["notes"] = d.notes;
  // NaN is not JSON: write null.
  return j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
}

void write_diagnosis_report(const EffectDiagnosis& d, const std::filesystem::path& html,
                            const DiagnoseOptions& options) {
  const int N = d.joints();
  const JointSamples& s = d.samples;
  // Fitted in N·m; shown in the log's unit (mA for a log of currents).
  const DriveUnits& u = s.units;
  const std::string unit = u.name();
  const Eigen::MatrixXd residual_before = u.to_effort(d.residual_before);
  const Eigen::MatrixXd residual_after = u.to_effort(d.residual_after);
  HtmlReport page("tpf diagnose: " + s.source);
  if (s.simulated) page.mark_simulated();
  page.subtitle("effort unit " + unit +
                (d.heldout_method == "none" ? std::string("; nothing held out")
                                            : "; held out " + d.heldout_method + ", never fitted"));
  page.table(diagnosis_summary_table(d, options));
  std::vector<std::string> groups;
  BarSeries before{"before", {}, ""}, after{"after", {}, ""};
  for (int i = 0; i < N; ++i)
    for (int r = 0; r < 3; ++r) {
      std::string label = "j";  // appended piecewise: GCC 12 -Wrestrict false positive on a + b + c
      label.append(std::to_string(i + 1)).append(" ").append(kRegimeNames[r]);
      groups.push_back(label);
      before.values.push_back(u.to_effort(i, d.before[i][r].rmse()));
      after.values.push_back(u.to_effort(i, d.after[i][r].rmse()));
    }
  page.figure(bar_chart({"Held-out RMSE per joint and regime", "", unit, 900, 320, true}, groups,
                        {before, after}));

  page.open_details("Findings in full");
  page.list(d.findings);
  if (!d.notes.empty()) page.list(d.notes);
  page.close_details();
  page.open_details("Held-out residual per joint and regime, before and after");
  Table table;
  table.header = {"joint",      "regime",     "samples",   "RMSE before",
                  "std before", "RMSE after", "std after", "change"};
  table.percent_column = 7;
  for (int i = 0; i < N; ++i)
    for (int r = 0; r < 4; ++r) {
      const ResidualSums& b = d.before[i][r];
      const ResidualSums& a = d.after[i][r];
      table.rows.push_back(
          {std::to_string(i + 1), kRegimeNames[r], format_fixed(b.count, 0),
           format_number(u.to_effort(i, b.rmse())), format_number(u.to_effort(i, b.std())),
           format_number(u.to_effort(i, a.rmse())), format_number(u.to_effort(i, a.std())),
           format_percent_change(b.rmse(), a.rmse())});
    }
  table.caption = "Residual = effort − model, " + unit + ", held-out samples.";
  page.table(table);
  page.close_details();
  page.open_details("Every candidate tried, round by round");
  Table evidence;
  evidence.header = {"round", "candidate effect", "held-out SSE removed", "BIC change", "selected"};
  for (const CandidateTrial& t : d.trials)
    evidence.rows.push_back({std::to_string(t.round), t.title,
                             format_fixed(100 * t.improvement, 2) + " %",
                             format_number(t.bic_change), t.selected ? "yes" : ""});
  evidence.caption =
      "SSE over the moving held-out samples of the joints the effect acts on; selected when it "
      "removes at least 10 % and the BIC falls.";
  page.table(evidence);
  page.close_details();
  page.open_details("Residual over time per joint, and against each effect's term");

  for (int i = 0; i < N; ++i) {
    page.figure(line_plot({"Joint " + std::to_string(i + 1) + ": residual over time (held-out)",
                           "t [s]", unit, 900, 260, false},
                          {heldout_series(s, "before", s.t, residual_before.col(i)),
                           heldout_series(s, "after", s.t, residual_after.col(i))}));
  }
  for (std::size_t e = 0; e < d.selected.size(); ++e) {
    const FeatureGroup& g = d.groups[d.selected[e]];
    const int i = !g.joints.empty() ? g.joints.back() : g.joint < 0 ? N - 1 : g.joint;
    const Eigen::VectorXd term = d.effect_terms[e].col(i) / u.newton_metres_per_unit(i);
    page.figure(
        scatter_plot({g.title + ": residual against the fitted term", "fitted term [" + unit + "]",
                      "residual [" + unit + "]", 900, 320, false},
                     {heldout_series(s, "before", term, residual_before.col(i)),
                      heldout_series(s, "after", term, residual_after.col(i))}),
        "Before, the residual follows the term (slope 1); after adding it, it is flat.");
  }
  page.close_details();
  page.paragraph(
      "Every number: tpf diagnose --json (the demo writes diagnosis.json beside this "
      "page).");
  page.write(html);
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
