#include "offline/diagnose/diagnose.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <utility>

#include "offline/diagnose/cad_payload_check.hpp"
#include "offline/diagnose/coupled_motor_fit.hpp"
#include "offline/diagnose/diagnosis_findings.hpp"
#include "offline/diagnose/effect_selection.hpp"
#include "offline/diagnose/neighbour_load_choice.hpp"
#include "offline/diagnose/residual_analysis.hpp"
#include "offline/diagnose/ripple_refit.hpp"
#include "offline/effects/effect_columns.hpp"
#include "offline/fit/parallel_jobs.hpp"
#include "offline/identify/identification_setup.hpp"
#include "offline/identify/inertia_prior.hpp"
#include "offline/report/text_format.hpp"
#include "offline/samples/held_out_rows.hpp"
#include "offline/samples/repeated_motion.hpp"
#include "offline/samples/sample_unit_check.hpp"
#include "tpf/common/error.hpp"
#include "tpf/dynamics/regressor.hpp"
#include "tpf/model/robot_description.hpp"

namespace tpf::offline {
namespace {

/// θ's coefficients of the groups of the family type Family, zero elsewhere.
template <typename Family>
Eigen::VectorXd only_family(const std::vector<FeatureGroup>& groups, const Eigen::VectorXd& theta) {
  Eigen::VectorXd part = Eigen::VectorXd::Zero(theta.size());
  for (const FeatureGroup& g : groups)
    if (g.key == Family::key)
      for (int c : g.columns)
        part[c] = theta[c];
  return part;
}

/// θ of `groups`' columns (`features` of them) of identify's declared fit on the training rows:
/// its rigid body (Identification::judged) and sliding friction levels (judged_linear: a coupled
/// motor's in its motor friction columns, the others' in their joints'), zero elsewhere (the
/// friction held at rest is fitted at rest, on top of it).
Eigen::VectorXd identified_theta(const ModelX& model, const std::vector<FeatureGroup>& groups,
                                 int features, const Identification& identified) {
  using Friction = JointFrictionColumns;
  using Motor = MotorFrictionColumns;
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(features);
  for (const FeatureGroup& g : groups)
    if (g.key == RigidBodyColumns::key) {
      for (std::size_t i = 0; i < g.columns.size(); ++i)
        theta[g.columns[i]] = identified.judged.base_values[static_cast<Eigen::Index>(i)];
    } else if (g.key == Friction::key && !motor_is_coupled(model, g.joint)) {
      theta[g.columns[Friction::kCoulomb]] = identified.judged_linear.coulomb[g.joint];
      theta[g.columns[Friction::kViscous]] = identified.judged_linear.viscous[g.joint];
    } else if (g.key == Motor::key) {
      for (int m = 0; m < model.joint_count(); ++m)
        if (motor_is_coupled(model, m)) {
          theta[g.columns[2 * m + Motor::kCoulomb]] = identified.judged_linear.coulomb[m];
          theta[g.columns[2 * m + Motor::kViscous]] = identified.judged_linear.viscous[m];
        }
    }
  return theta;
}

/// The declared columns identify fits (and the friction held at rest): with coupled motors,
/// their friction on the motor's velocity instead of their joint's, as identify has it.
std::vector<int> fitted_declared_columns(const ModelX& model,
                                         const std::vector<FeatureGroup>& groups) {
  std::vector<int> columns;
  for (const FeatureGroup& g : groups) {
    if (!g.declared) continue;
    if (g.key == JointFrictionColumns::key && motor_is_coupled(model, g.joint))
      columns.push_back(g.columns[JointFrictionColumns::kHeldAtRest]);
    else if (g.key == MotorFrictionColumns::key) {
      for (int m = 0; m < model.joint_count(); ++m)
        if (motor_is_coupled(model, m))
          columns.insert(columns.end(), g.columns.begin() + 2 * m, g.columns.begin() + 2 * m + 2);
    } else
      columns.insert(columns.end(), g.columns.begin(), g.columns.end());
  }
  return columns;
}

/// Throws tpf::Error unless `identified` was identified on `s` with the rigid-body base `base`.
void require_identified_on(const Identification& identified, const JointSamples& s,
                           const BaseParameters& base) {
  const NominalModelX& judged = identified.judged;
  bool same_base = judged.base_count == base.size();
  for (int i = 0; same_base && i < base.size(); ++i)
    same_base = judged.base_columns[i] == base.independent[static_cast<std::size_t>(i)];
  if (identified.residual.rows() != s.size() || identified.residual.cols() != s.joints() ||
      !same_base)
    throw Error(s.source + ": diagnose was handed an identification of other samples (" +
                std::to_string(identified.residual.rows()) + " × " +
                std::to_string(identified.residual.cols()) + " residual for " +
                std::to_string(s.size()) + " samples of " + std::to_string(s.joints()) +
                " joints) or of another rigid-body base; identify on the setup diagnose takes");
}

CandidateInputs candidate_inputs(const ModelX& model, const IdentificationSetup& setup,
                                 const JointSamples& s, const ResidualAnalysis& analysis,
                                 const Identification& identified,
                                 const Eigen::MatrixXd& declared_residual,
                                 const std::vector<int>& dead_joints, double static_velocity) {
  CandidateInputs inputs;
  inputs.enabled = true;
  inputs.dead_joints.assign(static_cast<std::size_t>(model.joint_count()), 0);
  for (int j : dead_joints)
    inputs.dead_joints[static_cast<std::size_t>(j - 1)] = 1;
  inputs.ripple_cycles = analysis.ripple_cycles;
  inputs.ripple_motor_cycles = analysis.ripple_motor_cycles;
  inputs.ripple_periods = analysis.ripple_periods;
  inputs.ripple_motor_periods = analysis.ripple_motor_periods;
  // Ripple is periodic in an angle: a prismatic joint (q in m) has no revolution to count over.
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.is_prismatic(j)) inputs.ripple_cycles[j] = inputs.ripple_motor_cycles[j] = 0.0;
  inputs.prediction_rate = analysis.effort_lag.column;
  inputs.effort_lag_s = analysis.effort_lag.lag_s;
  inputs.abs_gravity = setup.abs_gravity ? *setup.abs_gravity : gravity_load(model, s);
  inputs.neighbour_load_source = choose_neighbour_loads(s, declared_residual, inputs.abs_gravity);
  inputs.reference_temperature =
      s.temperature.cols() == s.joints()
          ? s.temperature.col(0).array().isFinite().select(s.temperature.col(0).array(), 0).mean()
          : 25.0;
  inputs.viscous = identified.judged_linear.viscous.cwiseMax(0.0);
  inputs.coupled_motors = fit_coupled_motors(model, setup.base, s, declared_residual,
                                             identified.joint_weights, static_velocity);
  return inputs;
}

std::string file_names(const Log& log, const std::vector<std::size_t>& files) {
  std::string text;
  for (std::size_t i = 0; i < files.size(); ++i)
    text += (i ? " + " : "") + std::filesystem::path(log.file_path(files[i])).filename().string();
  return text;
}

/// The held-out split in a sentence, with the repeated motions that grouped files.
std::string split_sentence(const Log& log, const JointSamples& s, const DiagnoseOptions& o) {
  const std::vector<std::vector<std::size_t>>& groups = s.heldout_file_groups;
  if (groups.empty()) return {};
  const double heldout_share =
      static_cast<double>(std::count(s.heldout.begin(), s.heldout.end(), 1)) /
      static_cast<double>(std::max<std::size_t>(s.heldout.size(), 1));
  std::string text;
  if (groups.size() == 1) {
    text = format_sentence(
        "Not held out by file: every file repeats one motion, so a fit on some would be scored "
        "on their own motion; the files are split as one log, in interleaved %g s blocks, 1 in "
        "%.0f held out (%.0f %% of the samples).",
        o.samples.block_s, o.samples.heldout_every, 100 * heldout_share);
  } else {
    const std::vector<std::size_t>& held = groups[s.heldout_group];
    text = "Held out by file: " + file_names(log, held) + " (fitted on the other files)";
    text += "; for the transfer test, one at a time:";
    for (std::size_t g = 0; g < groups.size(); ++g)
      if (g != s.heldout_group) {
        text += text.back() == ':' ? " " : "; ";
        text += file_names(log, groups[g]);
      }
    text += ".";
  }
  // Appended piece by piece (a chain of string + string trips GCC 12's -Wrestrict here).
  for (const RepeatedMotion& r : s.repeats) {
    text += " ";
    text += file_names(log, {r.second});
    text += " repeats the motion of ";
    text += file_names(log, {r.first});
    text += format_sentence(
        " (RMS of Δq over their common %.0f samples ≤ %.2g rad on every "
        "joint, below %.2g rad)",
        static_cast<double>(r.common_samples), r.rms_position_difference,
        o.samples.repeat_tolerance);
    text += groups.size() > 1
                ? ", so they are held out together: a fit on one would be scored on its own motion."
                : ".";
  }
  return text;
}

/// How rows are held out, in a phrase: by file (which) or by time blocks (their length).
std::string heldout_method(const Log& log, const JointSamples& s, const DiagnoseOptions& o) {
  if (!holds_rows_out(s)) return "none";
  if (s.heldout_file_groups.size() > 1)
    return "by file: " + file_names(log, s.heldout_file_groups[s.heldout_group]);
  return format_sentence("by time blocks: 1 in %.0f of interleaved %g s blocks",
                         o.samples.heldout_every, o.samples.block_s);
}

/// The folds a candidate's gain must transfer to (each group of files but the selection's held
/// out in turn, fitted on the rest), and every held-out group (the selection's first) scored only
/// outside the range of q its fit saw.
void held_out_folds(const Log& log, const EffectDesign& design, const JointSamples& s,
                    std::vector<TransferFold>& transfer, std::vector<OutsideFold>& outside) {
  const std::vector<std::vector<std::size_t>>& groups = s.heldout_file_groups;
  if (groups.size() < 2) return;
  std::vector<std::size_t> order{s.heldout_group};
  for (std::size_t g = 0; g < groups.size(); ++g)
    if (g != s.heldout_group) order.push_back(g);
  for (std::size_t g : order) {
    JointSamples fold = s;
    fold.heldout = file_group_rows(log, groups[g]);
    const std::string name = file_names(log, groups[g]);
    if (g != s.heldout_group) transfer.push_back({name, design.accumulate(fold)});
    std::vector<char> fit_rows(fold.heldout.size());
    for (std::size_t k = 0; k < fit_rows.size(); ++k)
      fit_rows[k] = !fold.heldout[k];
    const std::vector<std::pair<double, double>> range = position_range(fold, fit_rows);
    for (int j = 0; j < fold.joints(); ++j)
      for (Eigen::Index k = 0; k < fold.size(); ++k)
        if (fold.heldout[static_cast<std::size_t>(k)] && fold.q(k, j) >= range[j].first &&
            fold.q(k, j) <= range[j].second)
          fold.regimes[j][k] = Regime::Invalid;
    outside.push_back({name, design.accumulate(fold)});
  }
}

/// The candidate library's design and Grams.
struct CandidateDesign {
  std::unique_ptr<EffectDesign> design;
  DesignGrams grams;
};

/// The candidate design on `inputs`, made again with the refitted frequencies where an output
/// ripple with few periods in view moves (refitted_ripple_frequencies: the declared columns
/// fitted beside it with `selection`'s rows and weights and the robot file's inertia prior at
/// `prior_strength`).
CandidateDesign candidate_design(const ModelX& model, const IdentificationSetup& setup,
                                 const JointSamples& s,
                                 const std::shared_ptr<const SampleRegressors>& regressors,
                                 CandidateInputs inputs, FitSelection selection,
                                 double prior_strength, double threshold) {
  CandidateDesign out{
      std::make_unique<EffectDesign>(model, setup.base, s, regressors, inputs, threshold), {}};
  out.grams = out.design->accumulate(s);
  if (prior_strength > 0) {
    selection.prior = robot_file_prior(model, *out.design, setup.base);
    selection.prior.strength = prior_strength;
  }
  const RippleFrequencies refit = refitted_ripple_frequencies(
      *out.design, out.grams, s, fitted_declared_columns(model, out.design->groups()), selection);
  if (refit.cycles == inputs.ripple_cycles) return out;
  inputs = out.design->candidates();
  inputs.ripple_cycles = refit.cycles;
  inputs.ripple_periods = refit.periods;
  out.design = std::make_unique<EffectDesign>(model, setup.base, s, regressors, inputs, threshold);
  out.grams = out.design->accumulate(s);
  return out;
}

/// The part of `theta` outside the friction, which the friction curves are fitted beside.
Eigen::VectorXd non_friction_part(const std::vector<FeatureGroup>& groups,
                                  const Eigen::VectorXd& theta) {
  Eigen::VectorXd part = theta;
  for (const FeatureGroup& g : groups)
    if (g.written_to == WrittenTo::kFriction || g.written_to == WrittenTo::kNothing ||
        g.written_to == WrittenTo::kRobotFile)
      for (int c : g.columns)
        part[c] = 0.0;
  return part;
}

/// The effort predictions pass 4 needs, in one pass over the samples.
struct EffectPredictions {
  Eigen::MatrixXd selected, declared;  ///< the selected and the declared linear models
  std::vector<Eigen::MatrixXd> terms;  ///< per selected effect, as the written model has it
  Eigen::MatrixXd non_friction;        ///< written, outside the friction (curves fit it)
  Eigen::MatrixXd final_non_friction;  ///< non_friction of the model refitted on every row
};

/// `written`: the written model adds effects to the declared one (else it is identify's, and
/// `non_friction` is not predicted); `refitted`: it is refitted on every row.
EffectPredictions predict_effects(const EffectDesign& design, const EffectDiagnosis& d,
                                  const EffectSelection& sel, bool written, bool refitted) {
  std::vector<Eigen::VectorXd> thetas{sel.theta_selected, sel.theta_before};
  for (std::size_t e = 0; e < d.selected.size(); ++e) {
    // A written effect's term as the written model holds it; the others as selected.
    const Eigen::VectorXd& from = d.claims[e].written ? sel.theta_written : sel.theta_selected;
    Eigen::VectorXd part = Eigen::VectorXd::Zero(design.features());
    for (int c : d.groups[d.selected[e]].columns)
      part[c] = from[c];
    thetas.push_back(part);
  }
  if (written) thetas.push_back(non_friction_part(d.groups, sel.theta_written));
  if (written && refitted) thetas.push_back(non_friction_part(d.groups, sel.theta_final));
  std::vector<Eigen::MatrixXd> p = design.predict_each(d.samples, thetas);
  EffectPredictions out;
  out.selected = std::move(p[0]);
  out.declared = std::move(p[1]);
  for (std::size_t e = 0; e < d.selected.size(); ++e)
    out.terms.push_back(std::move(p[e + 2]));
  const std::size_t next = d.selected.size() + 2;
  if (written) out.non_friction = std::move(p[next]);
  if (written && refitted) out.final_non_friction = std::move(p[next + 1]);
  return out;
}

/// The linear model of the groups `theta` holds as a nominal model: rigid body (+ a payload
/// folded into it), friction levels, and the effects the run time evaluates (each group written
/// by its effect type). Returns the linear friction the curves start from; `load_selected` when
/// load-dependent friction is in it.
StribeckParametersX write_effects(const std::vector<FeatureGroup>& groups,
                                  const Eigen::VectorXd& theta, const BaseParameters& base,
                                  const CandidateInputs& inputs, NominalModelX& nominal,
                                  bool& load_selected) {
  const int joints = nominal.model.joint_count();
  Eigen::VectorXd payload = Eigen::VectorXd::Zero(11 * joints);
  StribeckParametersX linear;
  linear.resize(joints);
  WrittenModel written{nominal, linear, payload, base, inputs, false};
  for (const FeatureGroup& g : groups)
    write_group(g, theta, written);
  const Eigen::VectorXd payload_base = base.project(payload);
  for (int i = 0; i < base.size(); ++i)
    nominal.base_values[i] += payload_base[i];
  load_selected = written.load_selected;
  return linear;
}

/// The written model refitted on every row, held-out ones included (EffectSelection::theta_final,
/// `non_friction` its prediction outside the friction), each joint's friction curve or linear
/// fit as chosen on the held-out rows (`judged`): what the parameter file gets once the
/// selection and the curves are judged.
NominalModelX refitted_on_every_row(const std::vector<FeatureGroup>& groups,
                                    const Eigen::VectorXd& theta_final,
                                    const Eigen::MatrixXd& non_friction, const BaseParameters& base,
                                    const CandidateInputs& inputs, const JointSamples& s,
                                    const ModelX& model, const FrictionCurves& judged,
                                    bool fit_load, int samples_per_joint) {
  const Eigen::MatrixXd* coupling = model.coupled ? &model.coupling : nullptr;
  NominalModelX final_model;
  final_model.model = model;
  final_model.resize(model.joint_count());
  final_model.base_count = base.size();
  bool load_selected = false;
  const StribeckParametersX linear =
      write_effects(groups, theta_final, base, inputs, final_model, load_selected);
  final_model.friction =
      refit_friction_curves(s, non_friction, inputs.abs_gravity, linear, fit_load || load_selected,
                            samples_per_joint, judged, coupling);
  return final_model;
}

/// The robot file's (CAD) base parameters in the rigid body's columns, zero elsewhere.
Eigen::VectorXd cad_rigid_body(const ModelX& model, const BaseParameters& base,
                               const std::vector<FeatureGroup>& groups, Eigen::Index features) {
  const int n = model.joint_count();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd values =
      base.project(dynamic_parameters(model, zero, zero).head(11 * n).eval());
  Eigen::VectorXd cad = Eigen::VectorXd::Zero(features);
  for (const FeatureGroup& g : groups)
    if (g.key == RigidBodyColumns::key)
      for (int i = 0; i < base.size(); ++i)
        cad[g.columns[i]] = values[i];
  return cad;
}

/// Y(q, q̇, q̈) of every sample in the columns diagnose reads (a superset of identify's).
std::shared_ptr<const SampleRegressors> diagnosis_regressors(const ModelX& model,
                                                             const BaseParameters& base,
                                                             const JointSamples& s) {
  return std::make_shared<const SampleRegressors>(
      model,
      EffectDesign::regressor_columns(model.joint_count(), base.independent, true, model.coupled),
      s);
}

}  // namespace

IdentificationSetup prepare_diagnosis(const Log& log, const ModelX& model,
                                      const SampleOptions& options) {
  IdentificationSetup setup = prepare_identification(log, model, options);
  setup.regressors = diagnosis_regressors(model, setup.base, setup.samples);
  setup.gravity = std::make_shared<const Eigen::MatrixXd>(gravity_torque(model, setup.samples));
  setup.abs_gravity =
      std::make_shared<const Eigen::MatrixXd>(gravity_load(*setup.gravity, setup.samples));
  return setup;
}

Diagnosis diagnose(const Log& log, const ModelX& model, const DiagnoseOptions& options) {
  return diagnose(log, model, prepare_diagnosis(log, model, options.samples), options);
}

Diagnosis diagnose(const Log& log, const ModelX& model, IdentificationSetup setup,
                   const DiagnoseOptions& options) {
  if (!setup.regressors) setup.regressors = diagnosis_regressors(model, setup.base, setup.samples);
  if (!setup.abs_gravity)
    setup.abs_gravity = std::make_shared<const Eigen::MatrixXd>(gravity_load(model, setup.samples));
  const BaseParameters base = setup.base;
  const auto regressors = setup.regressors;
  const auto abs_gravity = setup.abs_gravity;
  const auto gravity = setup.gravity;
  IdentifyOptions identify_options;
  identify_options.samples = options.samples;
  identify_options.inertia_prior = options.inertia_prior;
  identify_options.progress = options.progress;
  Identification identified = identify(log, model, std::move(setup), identify_options);
  return diagnose(log, model,
                  {std::move(identified.samples), base, regressors, abs_gravity, gravity},
                  identified, options);
}

Diagnosis diagnose(const Log& log, const ModelX& model, IdentificationSetup setup,
                   const Identification& identified, const DiagnoseOptions& options) {
  require_identified_on(identified, setup.samples, setup.base);
  const auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  const int joints = model.joint_count();
  Diagnosis out;
  out.samples = std::move(setup.samples);
  out.heldout_split = split_sentence(log, out.samples, options);
  out.heldout_method = heldout_method(log, out.samples, options);
  const JointSamples& s = out.samples;
  std::vector<char> training(s.heldout.size());
  for (std::size_t k = 0; k < training.size(); ++k)
    training[k] = !s.heldout[k];
  out.fit_range = position_range(s, training);
  const double threshold = options.samples.regimes.static_velocity;

  // Identify's declared fit: its joint weights, inertia prior and linear fit θ.
  say("diagnose: pass 1/4: identify's declared model");
  FitSelection selection;  // fit on moving samples: friction at rest has memory
  selection.regimes = {false, true, true};
  selection.joint_weights = identified.joint_weights;
  out.inertia_prior = identified.inertia_prior;
  if (out.inertia_prior.asked && !(out.inertia_prior.floor > 0))
    out.notes.push_back(
        "inertia prior not applied: the robot file's own M(q) is not positive "
        "definite (smallest eigenvalue " +
        format_number(10 * out.inertia_prior.floor, 4) +
        " kg·m²), so it sets no floor to lift the fit's to");
  const auto regressors =
      setup.regressors ? setup.regressors : diagnosis_regressors(model, setup.base, s);
  const EffectDesign declared(model, setup.base, s, regressors, {}, threshold);
  // The residual of the linear fit the selection starts from (its standard errors are that
  // fit's: Identification::residual, with the friction curves, is less autocorrelated) and its
  // rigid-body part, in one pass.
  const Eigen::VectorXd theta =
      identified_theta(model, declared.groups(), declared.features(), identified);
  std::vector<Eigen::MatrixXd> linear =
      declared.predict_each(s, {theta, only_family<RigidBodyColumns>(declared.groups(), theta)});
  linear[0] = s.effort - linear[0];

  say("diagnose: pass 2/4: residual analysis");
  const ResidualAnalysis analysis = analyse_residual(s, linear[0], linear[1], model.gear_ratio,
                                                     options.samples.acceleration_cutoff_hz);
  out.noise_floor = analysis.noise_floor;
  out.motion_noise = analysis.motion_noise;
  out.model_band_hz = options.samples.acceleration_cutoff_hz;
  out.notes.insert(out.notes.end(), analysis.notes.begin(), analysis.notes.end());
  if (s.temperature.cols() != joints)
    out.notes.push_back("temperature-dependent friction not checked: the log has no temp<j>");
  if (joints == 1) out.notes.push_back("coupling between joints not checked: one joint");

  // A dead effort channel (mostly exact zeros) is kept out of every candidate of its joint.
  const LogChecks checks =
      check_sample_units(model, s, setup.gravity ? *setup.gravity : Eigen::MatrixXd());
  for (const std::string& problem : checks.problems)
    if (problem.find("dead effort channel") != std::string::npos)
      out.notes.push_back(problem + ": no candidate effect is tried on it");

  say("diagnose: pass 3/4: candidate effects");
  const CandidateDesign candidates =
      candidate_design(model, setup, s, regressors,
                       candidate_inputs(model, setup, s, analysis, identified, linear[0],
                                        checks.dead_joints, threshold),
                       selection, out.inertia_prior.judged_strength, threshold);
  const EffectDesign& design = *candidates.design;
  const DesignGrams& grams = candidates.grams;
  const CandidateInputs& inputs = design.candidates();  // not copied: |G(q)| of every sample
  out.coupled_motors = inputs.coupled_motors;
  out.effort_lag_s = inputs.effort_lag_s;
  FitSelection every = selection;  // the written model's final refit
  every.heldout_rows = true;
  if (out.inertia_prior.judged_strength > 0 || out.inertia_prior.written_strength > 0) {
    selection.prior = robot_file_prior(model, design, setup.base);
    every.prior = selection.prior;
    selection.prior.strength = out.inertia_prior.judged_strength;
    every.prior.strength = out.inertia_prior.written_strength;
  }
  out.groups = design.groups();
  std::vector<TransferFold> transfer;
  std::vector<OutsideFold> outside;
  held_out_folds(log, design, s, transfer, outside);
  EffectSelection sel = select_effects(
      grams, transfer, outside, out.groups, fitted_declared_columns(model, out.groups),
      identified_theta(model, out.groups, design.features(), identified), selection, every,
      analysis.variance_inflation, options);
  out.trials = std::move(sel.trials);
  out.selected = sel.selected;
  out.claims = sel.claims;
  out.before = sel.before;
  out.after = sel.after;

  say("diagnose: pass 4/4: refit with the selected effects");
  out.refitted = identified.refitted;
  const bool adds =
      std::any_of(out.claims.begin(), out.claims.end(), [](const Claim& c) { return c.written; });
  EffectPredictions p = predict_effects(design, out, sel, adds, out.refitted);
  out.residual_after = std::move(p.selected);  // in place: effort − prediction
  out.residual_after = s.effort - out.residual_after;
  out.residual_before = std::move(p.declared);
  out.residual_before = s.effort - out.residual_before;
  out.effect_terms = std::move(p.terms);
  // The declared model as identify fits it, and what it scores held out.
  out.declared = identified.judged;
  out.written_before = identified.heldout;
  if (!adds) {  // nothing to write beside the declared model: identify's is the written model
    out.nominal = identified.nominal;
    out.judged = identified.judged;
    out.residual_written = identified.residual;
    out.written_after = identified.heldout;
  } else {
    NominalModelX& judged = out.judged;
    judged.model = model;
    judged.resize(joints);
    judged.base_count = setup.base.size();
    bool load_selected = false;
    const StribeckParametersX linear =
        write_effects(out.groups, sel.theta_written, setup.base, inputs, judged, load_selected);
    // The friction curves fitted as identify fits the declared model's.
    const bool fit_load = identified.fit_load_friction || load_selected;
    const FrictionCurves curves = fit_friction_curves(
        s, p.non_friction, inputs.abs_gravity, linear, fit_load,
        identified.friction_samples_per_joint, model.coupled ? &model.coupling : nullptr);
    judged.friction = curves.parameters;
    for (const std::string& note : curves.notes)
      out.notes.push_back("friction curve: " + note);
    out.residual_written = nominal_residual(judged, s);
    out.written_after = split_regime_stats(s, out.residual_written, true);
    out.nominal = judged;
    if (out.refitted)
      out.nominal = refitted_on_every_row(out.groups, sel.theta_final, p.final_non_friction,
                                          setup.base, inputs, s, model, curves, fit_load,
                                          identified.friction_samples_per_joint);
  }

  out.cad_payload = judge_cad_payload(
      grams, out.groups, cad_rigid_body(model, setup.base, out.groups, design.features()),
      out.selected, transfer, selection, analysis.variance_inflation, options);
  out.findings = diagnosis_findings(out, options);
  return out;
}

}  // namespace tpf::offline
