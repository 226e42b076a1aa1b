#include "offline/diagnose/diagnosis_summary.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/report/text_format.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

/// "position ripple (10 periods/rev of q)" from "position ripple, joint 3 (10 periods/rev of q)".
std::string effect_name(const std::string& title) {
  const std::size_t at = title.find(", joint ");
  if (at == std::string::npos) return title;
  std::size_t end = at + 8;
  while (end < title.size() && std::isdigit(static_cast<unsigned char>(title[end])))
    ++end;
  return title.substr(0, at) + title.substr(end);
}

std::string joint_cell(int joint) {
  return joint < 0 ? "all" : std::to_string(joint + 1);
}

std::string gain_cell(double share) {
  return std::isfinite(share) ? format_fixed(100 * share, 1) + " %" : "–";
}

std::string percent(double share) {
  return format_fixed(100 * share, 0) + " %";
}

/// Why a claim is or is not in the parameter file.
std::string claim_reason(const EffectDiagnosis& d, const Claim& c) {
  const FeatureGroup& g = d.groups[c.groups[0]];
  if (!c.written && g.written_to == WrittenTo::kNothing)
    return "the run time cannot evaluate it (past samples, temperature)";
  if (!c.written && g.written_to == WrittenTo::kRobotFile)
    return "a motor coupling is the robot file's to declare (coupled_to)";
  if (!c.written && !c.scored_joints.empty()) return "the data cannot tell which joint it acts on";
  if (!c.written) return "ambiguous with another effect on this log";
  const bool untested = std::any_of(d.trials.begin(), d.trials.end(), [&](const CandidateTrial& t) {
    return t.selected && t.title == g.title && t.outside_untested();
  });
  return untested ? "passes every test; not tested beyond the fitted q range"
                  : "passes the held-out, BIC and standard-error tests";
}

/// Why a candidate's last trial did not select it; `best` is its largest gain in any round.
std::string rejection_reason(const CandidateTrial& t, double best, const DiagnoseOptions& o) {
  if (t.improvement < o.min_improvement)
    return best >= o.min_improvement ? "the effects chosen before it explain it"
                                     : "removes less than " + percent(o.min_improvement);
  if (t.bic_change >= 0) return "the held-out BIC does not fall";
  if (t.wald < o.min_standard_errors)
    return "coefficient within " + format_number(o.min_standard_errors, 2) +
           " standard errors of zero";
  if (t.fails_alone(o))
    return "alone on the model it removes less than " + percent(o.min_improvement);
  if (t.fails_transfer(o)) return "another held-out file gets worse";
  if (t.fails_outside(o)) return "fails outside the range of q it was fitted on";
  if (t.stands_in(o)) return "stands in for " + t.stand_in_for + ", which does not transfer";
  return "passes, but the selection stopped at its limit";
}

void add_payload_row(Table& table, const EffectDiagnosis& d, const DiagnoseOptions& o) {
  const CadPayloadCheck& c = d.cad_payload;
  if (!(c.improvement >= o.min_improvement)) return;
  std::string why = "the identified rigid body absorbs it: not missing";
  if (c.ambiguous())
    why = "collinear with a selected effect: not claimed";
  else if (!c.claimed && std::isfinite(c.transfer_improvement) &&
           c.transfer_improvement < o.min_improvement)
    why = "does not transfer between files: not claimed";
  else if (!c.claimed)
    why = "fails the BIC or standard-error test: not claimed";
  table.rows.push_back({"payload on the last link, against the robot file's inertias", "all",
                        gain_cell(c.improvement), "no", why});
}

void add_rejected_rows(Table& table, const EffectDiagnosis& d, const DiagnoseOptions& o,
                       int max_rejected) {
  // Per candidate (its title), its last trial and its best gain in any round.
  std::map<std::string, std::pair<const CandidateTrial*, double>> candidates;
  for (const CandidateTrial& t : d.trials) {
    const auto it = candidates.try_emplace(t.title, &t, t.improvement).first;
    it->second.first = &t;
    it->second.second = std::max(it->second.second, t.improvement);
  }
  std::vector<std::pair<const CandidateTrial*, double>> rejected;
  for (const auto& candidate : candidates) {
    const std::string& title = candidate.first;
    const auto& entry = candidate.second;
    const bool claimed = std::any_of(d.selected.begin(), d.selected.end(),
                                     [&](int g) { return d.groups[g].title == title; });
    if (!claimed && entry.first->key != "payload" && entry.second >= 0.5 * o.min_improvement)
      rejected.push_back(entry);
  }
  std::sort(rejected.begin(), rejected.end(),
            [](const auto& a, const auto& b) { return a.second > b.second; });
  if (rejected.size() > static_cast<std::size_t>(max_rejected))
    rejected.resize(static_cast<std::size_t>(max_rejected));
  for (const auto& [t, best] : rejected)
    table.rows.push_back({effect_name(t->title), joint_cell(t->joint), gain_cell(t->improvement),
                          "no", rejection_reason(*t, best, o)});
}

}  // namespace

Table diagnosis_summary_table(const EffectDiagnosis& d, const DiagnoseOptions& o,
                              int max_rejected) {
  Table table;
  table.header = {"effect", "joint", "held-out gain", "written", "why"};
  table.caption =
      "Share of the held-out residual sum of squares each effect removes (its last "
      "round for those not claimed); every candidate in diagnosis.json.";
  for (const Claim& c : d.claims) {
    const FeatureGroup& g = d.groups[c.groups[0]];
    std::string name = effect_name(g.title);
    if (c.ambiguous()) name += " (or " + std::to_string(c.groups.size() - 1) + " other)";
    table.rows.push_back({name, joint_cell(g.joint), gain_cell(c.improvements[0]),
                          c.written ? "yes" : "no", claim_reason(d, c)});
  }
  add_payload_row(table, d, o);
  add_rejected_rows(table, d, o, max_rejected);
  return table;
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
