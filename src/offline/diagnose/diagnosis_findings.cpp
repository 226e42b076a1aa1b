#include "offline/diagnose/diagnosis_findings.hpp"

#include <algorithm>
#include <cmath>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/regimes/regime.hpp"
#include "offline/report/text_format.hpp"
#include "offline/samples/joint_samples.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

std::string payload_finding(const CadPayloadCheck& c) {
  return format_sentence(
             "Against the robot file's inertias: a payload of %.3g ± %.2g kg on the last link",
             c.mass, c.mass_standard_error) +
         format_sentence(" at (%.3f, %.3f, %.3f) m in its frame", c.centre.x(), c.centre.y(),
                         c.centre.z()) +
         format_sentence(
             " — removes %.1f %% of the held-out residual sum of squares of the CAD "
             "model beside the selected effects (absorbed by the identified rigid body, so not a "
             "missing effect of the identified model).",
             100 * c.improvement);
}

/// A payload that the selected effects explain as well: no claim, the alternatives named.
std::string ambiguous_payload_finding(const EffectDiagnosis& d, const CadPayloadCheck& c) {
  std::string text =
      "Against the robot file's inertias: ambiguous between a payload on the last "
      "link and ";
  for (std::size_t i = 0; i < c.ambiguous_with.size(); ++i)
    text += (i ? " and " : "") + d.groups[c.ambiguous_with[i]].title +
            format_sentence(" (cos² %.2f)", c.ambiguous_shares[i]);
  return text + format_sentence(
                    ": without it a payload would be claimed; beside it the payload is not "
                    "(%.3g ± %.2g kg, removing %.1f %% of the held-out residual sum of squares), "
                    "and on this log their columns are nearly collinear, so no payload is "
                    "claimed.",
                    c.mass, c.mass_standard_error, 100 * c.improvement);
}

/// A payload that passes on the selection's held-out file but not on another held out in turn.
std::string untransferred_payload_finding(const CadPayloadCheck& c) {
  return format_sentence(
             "Against the robot file's inertias: a payload of %.3g ± %.2g kg on the last link "
             "removes %.1f %% of the held-out residual sum of squares beside the selected "
             "effects, ",
             c.mass, c.mass_standard_error, 100 * c.improvement) +
         format_sentence("but %.1f %% on ", 100 * c.transfer_improvement) + c.transfer_file +
         " held out one at a time: it does not transfer between files, so it is not the arm's and "
         "is not claimed.";
}

/// The trial that selected the claim's group.
const CandidateTrial* selected_trial(const EffectDiagnosis& d, const Claim& c) {
  for (const CandidateTrial& t : d.trials)
    if (t.selected && t.title == d.groups[c.groups[0]].title) return &t;
  return nullptr;
}

/// "joints 1 and 2" of a claim scored on several joints.
std::string joint_list(const std::vector<int>& joints) {
  std::string text = "joints ";
  for (std::size_t i = 0; i < joints.size(); ++i)
    text += (i == 0 ? "" : i + 1 == joints.size() ? " and " : ", ") + std::to_string(joints[i] + 1);
  return text;
}

/// An ambiguous claim between candidates of different joints, each gain on the same joints.
std::string cross_joint_finding(const EffectDiagnosis& d, const Claim& c,
                                const std::string& coefficients) {
  std::string text = "Ambiguous between ";
  for (std::size_t i = 0; i < c.groups.size(); ++i) {
    text += (i ? " and " : "") + d.groups[c.groups[i]].title;
    text += std::isfinite(c.improvements[i])
                ? format_sentence(" (removes %.1f %%)", 100 * c.improvements[i])
                : std::string(" (declared)");
  }
  return text + " of the held-out residual sum of squares of " + joint_list(c.scored_joints) +
         ": on this log their parts outside the model are nearly collinear (through the rigid "
         "body they share), so the data cannot tell which joint it acts on and no coefficient "
         "means much alone (the first: " +
         coefficients + "); robot-file inertias known to be right would tell them apart.";
}

std::string claim_finding(const EffectDiagnosis& d, const Claim& c) {
  const FeatureGroup& g = d.groups[c.groups[0]];
  std::string coefficients;
  for (std::size_t i = 0; i < c.coefficients.size(); ++i)
    coefficients +=
        (i ? ", " : "") + format_sentence("%.4g ± %.2g", c.coefficients[i], c.standard_errors[i]);
  std::string text;
  if (!c.ambiguous()) {
    text = "Found: " + g.title +
           format_sentence(" — removes %.1f %% of the held-out residual sum of squares",
                           100 * c.improvements[0]) +
           (g.joints.empty() ? std::string() : " of " + joint_list(g.joints)) +
           (std::isfinite(c.beside_improvement)
                ? format_sentence(" (%.1f %% beside an offset and a slope of its joint)",
                                  100 * c.beside_improvement)
                : std::string()) +
           "; coefficients (N·m per unit of the term) " + coefficients + " (" +
           (g.column_names.size() == 1 ? g.column_names[0] : g.key) + ").";
  } else if (!c.scored_joints.empty()) {
    text = cross_joint_finding(d, c, coefficients);
  } else {
    text = "Ambiguous between " + g.title +
           format_sentence(" (removes %.1f %%)", 100 * c.improvements[0]);
    for (std::size_t i = 1; i < c.groups.size(); ++i) {
      const FeatureGroup& other = d.groups[c.groups[i]];
      text += " and " + other.title;
      text += std::isfinite(c.improvements[i])
                  ? format_sentence(" (removes %.1f %%)", 100 * c.improvements[i])
                  : std::string(other.declared ? " (declared)" : " (in the model)");
    }
    text += g.indistinct_from_beside
                ? std::string(
                      ": the joint's range of motion holds under one period of it, which an "
                      "offset and a slope stand for as well, so the data cannot tell which it is "
                      "nor the ripple's frequency, and no coefficient means much alone (the "
                      "first: ")
                : format_sentence(
                      ": on this log their columns are nearly collinear (share outside the "
                      "model %.3f), so the data cannot tell which it is and no coefficient "
                      "means much alone (the first: ",
                      c.distinct_share);
    text += coefficients +
            "); a log with more range of motion, both directions and rests tells them apart.";
  }
  if (const CandidateTrial* t = selected_trial(d, c); t && t->extrapolates)
    text += std::isnan(t->outside_improvement)
                ? format_sentence(
                      " Its term extrapolates in q; no held-out file left the range "
                      "of q_%.0f the fit saw (%.3g … %.3g rad), so transfer outside "
                      "that range is not tested.",
                      g.joint + 1.0, d.fit_range[g.joint].first, d.fit_range[g.joint].second)
                : format_sentence(
                      " Its term extrapolates in q: on the %.0f held-out samples "
                      "of ",
                      t->outside_samples) +
                      t->outside_file +
                      format_sentence(" outside the range of q the fit saw it removes %.1f %%.",
                                      100 * t->outside_improvement);
  if (!c.written && g.written_to == WrittenTo::kRobotFile)
    text +=
        " Not written to the parameter file: a motor coupling is the robot file's to declare "
        "(the drive's coupled_to, then identify again); the friction cannot tell this motor from "
        "the other joint's rotating with the reciprocal ratio, only the robot's drawings can; the "
        "'written' table leaves it out.";
  else if (!c.written && g.written_to == WrittenTo::kNothing)
    text +=
        " Not written to the parameter file: the run-time nominal model cannot evaluate it "
        "(it keeps no past samples / has no temperature input); the 'written' table "
        "leaves it out.";
  else if (!c.written && !c.scored_joints.empty())
    text +=
        " Not written to the parameter file: which joint's term it is changes the rigid body "
        "fitted beside it; the written model is refitted without it.";
  else if (!c.written)
    text +=
        " Not written to the parameter file: the two would predict differently where this log "
        "cannot tell them apart (the other direction, outside its range of motion); the written "
        "model is refitted without it.";
  return text;
}

// Regimes the written model does worse in than the declared one, explained (RMSE in the log's
// unit).
void add_worsened_regimes(const EffectDiagnosis& d, std::vector<std::string>& findings) {
  const DriveUnits& u = d.samples.units;
  for (int j = 0; j < d.joints(); ++j)
    for (Regime r : {Regime::Static, Regime::StaticToKinetic, Regime::Moving}) {
      const double before = u.to_effort(j, d.written_before[j][r].rmse);
      const double after = u.to_effort(j, d.written_after[j][r].rmse);
      if (!(after > 1.02 * before)) continue;
      findings.push_back(
          "Joint " + std::to_string(j + 1) + ", " + std::string(regime_name(r)) +
          format_sentence(
              ": the written model's held-out RMSE rises from %.4g to %.4g (%+.0f %%). ", before,
              after, 100 * (after / before - 1)) +
          (r == Regime::Static
               ? "Effects are selected on motion; at rest the effort holds whatever friction the "
                 "motion left (memory) and the run time predicts none, so a term that shifts the "
                 "prediction (offset, spring, load) moves it away from that held friction."
               : "The friction curve refitted with the added effects does worse here than the "
                 "declared model's: the effects and the curve share these samples."));
    }
}

/// Whether `title` is named by a claim (added to the model in some round, or an alternative of
/// an ambiguous claim).
bool selected_in_a_round(const EffectDiagnosis& d, const std::string& title) {
  for (const Claim& c : d.claims)
    for (int g : c.groups)
      if (d.groups[g].title == title) return true;
  return false;
}

/// The trials `fails` refuses, the first of each title, leaving out those a claim names (tried
/// again in a later round, on a larger model, they passed).
template <typename Fails>
std::vector<const CandidateTrial*> refused_once(const EffectDiagnosis& d, Fails fails) {
  std::vector<const CandidateTrial*> refused;
  for (const CandidateTrial& t : d.trials) {
    if (!fails(t) || selected_in_a_round(d, t.title)) continue;
    const auto same_title = [&](const CandidateTrial* r) { return r->title == t.title; };
    if (std::none_of(refused.begin(), refused.end(), same_title)) refused.push_back(&t);
  }
  return refused;
}

// Periodic candidates that explain the residual beside their joint's offset and slope but, added
// to the model alone (what a claim writes), lower its held-out error too little, once each.
void add_not_alone(const EffectDiagnosis& d, const DiagnoseOptions& options,
                   std::vector<std::string>& findings) {
  const auto fails = [&](const CandidateTrial& t) {
    return t.fails_alone(options) && t.improvement >= options.min_improvement && t.bic_change < 0 &&
           t.wald >= options.min_standard_errors;
  };
  for (const CandidateTrial* trial : refused_once(d, fails)) {
    const CandidateTrial& t = *trial;
    findings.push_back(
        "Not claimed: " + t.title +
        format_sentence(
            " — beside an offset and a slope of its joint it removes %.1f %% of the "
            "held-out residual sum of squares, but added to the model alone, as it "
            "would be written, it changes it by %+.1f %% (claims need −%.0f %%): its gain "
            "needs the offset and slope beside it, which the model does not hold.",
            100 * t.improvement, -100 * t.model_improvement, 100 * options.min_improvement));
  }
}

// Candidates that passed on the held-out file but made another file worse, once each (not those
// a claim names: tried again in a later round, on a larger model, they passed).
void add_untransferred(const EffectDiagnosis& d, const DiagnoseOptions& options,
                       std::vector<std::string>& findings) {
  const auto fails = [&](const CandidateTrial& t) { return t.fails_transfer(options); };
  for (const CandidateTrial* trial : refused_once(d, fails)) {
    const CandidateTrial& t = *trial;
    findings.push_back(
        "Not claimed: " + t.title +
        format_sentence(" — removes %.1f %% of the held-out file's residual sum of squares, but "
                        "changes that of ",
                        100 * t.improvement) +
        t.transfer_file +
        format_sentence(", held out one at a time, by %+.1f %% (claims need −%.0f %% on every "
                        "file): it does not transfer between files.",
                        -100 * t.transfer_improvement, 100 * options.min_improvement));
  }
}

// Candidates that passed every test but explain only what a stronger candidate that failed the
// transfer test explained, once each: one explanation of that residual did not hold on another
// file, so no weaker one is claimed in its place.
void add_stand_ins(const EffectDiagnosis& d, const DiagnoseOptions& options,
                   std::vector<std::string>& findings) {
  const auto stands_in = [&](const CandidateTrial& t) { return t.stands_in(options); };
  for (const CandidateTrial* trial : refused_once(d, stands_in)) {
    const CandidateTrial& t = *trial;
    findings.push_back(
        "Not claimed: " + t.title +
        format_sentence(" — removes %.1f %% of the held-out residual sum of squares, but beside ",
                        100 * t.improvement) +
        t.stand_in_for +
        format_sentence(" it removes %.1f %%: it explains the residual that one explains, and "
                        "that one does not transfer between files (above), so neither is claimed.",
                        100 * t.beside_failed_improvement));
  }
}

// Candidates that passed on the held-out files but, extrapolated outside the fit's range of q,
// made the held-out samples there worse, once each.
void add_not_extrapolating(const EffectDiagnosis& d, const DiagnoseOptions& options,
                           std::vector<std::string>& findings) {
  const auto fails = [&](const CandidateTrial& t) { return t.fails_outside(options); };
  for (const CandidateTrial* trial : refused_once(d, fails)) {
    const CandidateTrial& t = *trial;
    findings.push_back(
        "Not claimed: " + t.title +
        format_sentence(" — removes %.1f %% of the held-out file's residual sum of squares, but "
                        "on the %.0f held-out samples of ",
                        100 * t.improvement, t.outside_samples) +
        t.outside_file +
        format_sentence(" whose q lies outside the range the fit saw it changes it by %+.1f %% "
                        "(claims need −%.0f %% there): its term, fitted over a range of q, does "
                        "not extrapolate.",
                        -100 * t.outside_improvement, 100 * options.min_improvement));
  }
}

// What no candidate explains: moving held-out RMSE over 3× the effort's noise in motion (above
// the model's band; the noise at rest where the joint has none), static over 3× the noise at
// rest (in the log's unit); thousands of times the noise: perhaps the effort's unit.
void add_unexplained(const EffectDiagnosis& d, std::vector<std::string>& findings) {
  constexpr double kUnitsSuspect = 1000;
  for (int j = 0; j < d.joints(); ++j) {
    const DriveUnits& u = d.samples.units;
    const double moving = u.to_effort(j, d.after[j][2].rmse());
    const double still = u.to_effort(j, d.after[j][0].rmse());
    const double floor = u.to_effort(j, d.noise_floor[j]);
    const double in_motion =
        j < d.motion_noise.size() ? u.to_effort(j, d.motion_noise[j]) : std::nan("");
    const double noise = std::isfinite(in_motion) ? in_motion : floor;
    if (std::isfinite(noise) && moving > 3 * noise) {
      std::string text =
          "Left unexplained on joint " + std::to_string(j + 1) +
          format_sentence(
              ": moving held-out RMSE %.3g is %.1f× the effort's noise in motion "
              "(%.3g",
              moving, moving / noise, noise) +
          (std::isfinite(in_motion)
               ? format_sentence(", above the model's %g Hz band; %.3g at rest)", d.model_band_hz,
                                 floor)
               : std::string(" at rest: the joint's effort in motion was not measured)"));
      text += "; no candidate of the library explains the rest.";
      const double least = std::isfinite(floor) ? std::min(noise, floor) : noise;
      if (moving > kUnitsSuspect * least)
        text += format_sentence(
            " An error %.0f× the noise is more than a missing effect usually leaves: check that "
            "the effort is in the unit the log declares (a current read as N·m, a torque "
            "constant or gear ratio off by a factor).",
            moving / least);
      findings.push_back(text);
    }
    if (std::isfinite(floor) && still > 3 * floor)
      findings.push_back(
          "Left unexplained on joint " + std::to_string(j + 1) +
          format_sentence(": static held-out RMSE %.3g is %.1f× the noise floor (%.3g): the "
                          "friction held at rest depends on the history of the motion (memory), "
                          "which no memoryless effect explains (the TCN compensator's job).",
                          still, still / floor, floor));
  }
}

}  // namespace

std::vector<std::string> diagnosis_findings(const EffectDiagnosis& d,
                                            const DiagnoseOptions& options) {
  std::vector<std::string> findings;
  if (!d.heldout_split.empty()) findings.push_back(d.heldout_split);
  if (d.cad_payload.claimed) findings.push_back(payload_finding(d.cad_payload));
  if (d.cad_payload.ambiguous()) findings.push_back(ambiguous_payload_finding(d, d.cad_payload));
  if (!d.cad_payload.claimed && d.cad_payload.transfer_improvement < options.min_improvement &&
      d.cad_payload.improvement >= options.min_improvement && d.cad_payload.mass > 0)
    findings.push_back(untransferred_payload_finding(d.cad_payload));
  const bool untransferred =
      std::any_of(d.trials.begin(), d.trials.end(), [&](const CandidateTrial& t) {
        return t.fails_transfer(options) || t.fails_outside(options);
      });
  const std::string nothing_held_out = nothing_held_out_note(d.samples, options.samples);
  if (d.selected.empty() && !nothing_held_out.empty())
    findings.push_back("No candidate effect can be claimed: " + nothing_held_out + ".");
  else if (d.selected.empty())
    findings.push_back(
        "No candidate effect is claimed: none lowers the held-out residual by the threshold (" +
        format_sentence("%.0f %%", 100 * options.min_improvement) +
        " of the residual sum of squares)" +
        (untransferred ? " and does so on every file held out one at a time and, for a term that "
                         "extrapolates in q, outside the range of q the fit saw (below)."
                       : "."));
  for (const Claim& c : d.claims)
    findings.push_back(claim_finding(d, c));
  add_not_alone(d, options, findings);
  add_untransferred(d, options, findings);
  add_stand_ins(d, options, findings);
  add_not_extrapolating(d, options, findings);
  add_worsened_regimes(d, findings);
  add_unexplained(d, findings);
  return findings;
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
