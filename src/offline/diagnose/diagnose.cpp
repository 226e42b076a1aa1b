#include "offline/diagnose/diagnose.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <utility>

#include "offline/diagnose/cad_payload_check.hpp"
#include "offline/diagnose/diagnosis_findings.hpp"
#include "offline/diagnose/effect_selection.hpp"
#include "offline/diagnose/residual_analysis.hpp"
#include "offline/effects/effect_columns.hpp"
#include "offline/fit/parallel_jobs.hpp"
#include "offline/identify/identification_setup.hpp"
#include "offline/identify/inertia_prior.hpp"
#include "offline/report/text_format.hpp"
#include "offline/samples/held_out_rows.hpp"
#include "offline/samples/repeated_motion.hpp"
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

/// Pass 1: the declared model fitted on motion (every 4th sample is plenty for the candidates'
/// inputs; selection and the before/after table use every sample), its residual, its rigid-body
/// prediction, and the joint weights 1/σ_j² of the fit; with an inertia prior, the strength the
/// fit then has: `given` (identify's) when it is a number, else the one identify would write
/// (choose_inertia_prior on the training rows, refit_with_inertia_prior on every row).
struct DeclaredFit {
  double prior_strength = 0;
  double min_mass_eigenvalue_without_prior = 0;
  std::string prior_choice;
  Eigen::VectorXd joint_weights;
  Eigen::VectorXd viscous;           ///< per joint: the fitted viscous coefficient b_j
  Eigen::MatrixXd residual;          ///< effort − declared prediction
  Eigen::MatrixXd rigid_prediction;  ///< its rigid-body part
};

/// The strength of the prior for every fit of diagnose (DeclaredFit), its M(q) without it and
/// why, into `fit`.
void declared_prior_strength(const ModelX& model, const BaseParameters& base,
                             const EffectDesign& declared, const JointSamples& s,
                             const DesignGrams& grams, const FitSelection& selection,
                             const RobotFileInertiaPrior& prior, double given, DeclaredFit& fit) {
  const std::vector<int> columns = declared.declared_columns();
  FitSelection every = selection;
  every.heldout_rows = true;
  if (std::isfinite(given)) {
    const PriorFit with = fit_with_inertia_prior_strength(model, declared, base, grams, columns,
                                                          every, &prior, given);
    fit.prior_strength = given;
    fit.min_mass_eigenvalue_without_prior = with.min_eigenvalue_without;
    fit.prior_choice = "identify's (chosen on its held-out rows)";
    return;
  }
  const PriorFit judged =
      choose_inertia_prior(model, declared, base, grams, columns, selection, &prior);
  const PriorFit written =
      holds_rows_out(s)
          ? refit_with_inertia_prior(model, declared, base, grams, columns, every, &prior, judged)
          : judged;
  fit.prior_strength = written.strength;
  fit.min_mass_eigenvalue_without_prior =
      std::min(judged.min_eigenvalue_without, written.min_eigenvalue_without);
  fit.prior_choice = judged.choice;
}

DeclaredFit fit_declared(const ModelX& model, const BaseParameters& base,
                         const EffectDesign& declared, const JointSamples& s,
                         FitSelection selection, const RobotFileInertiaPrior* prior,
                         double given_strength) {
  const DesignGrams grams = declared.accumulate(s, 4);
  Eigen::VectorXd theta = fit_columns(grams, declared.declared_columns(), selection);
  DeclaredFit fit;
  fit.joint_weights = moving_residual_weights(grams, theta);
  selection.joint_weights = fit.joint_weights;
  if (prior) {
    declared_prior_strength(model, base, declared, s, grams, selection, *prior, given_strength,
                            fit);
    selection.prior = prior->prior;
    selection.prior.strength = fit.prior_strength;
  }
  theta = fit_columns(grams, declared.declared_columns(), selection);
  std::vector<Eigen::MatrixXd> predictions =
      declared.predict_each(s, {theta, only_family<RigidBodyColumns>(declared.groups(), theta)});
  fit.residual = std::move(predictions[0]);  // in place: effort − prediction
  fit.residual = s.effort - fit.residual;
  fit.viscous.resize(declared.joints());
  for (const FeatureGroup& g : declared.groups())
    if (g.key == JointFrictionColumns::key)
      fit.viscous[g.joint] = std::max(theta[g.columns[JointFrictionColumns::kViscous]], 0.0);
  fit.rigid_prediction = std::move(predictions[1]);
  return fit;
}

CandidateInputs candidate_inputs(const ModelX& model, const IdentificationSetup& setup,
                                 const JointSamples& s, const ResidualAnalysis& analysis,
                                 const DeclaredFit& fit) {
  CandidateInputs inputs;
  inputs.enabled = true;
  inputs.ripple_cycles = analysis.ripple_cycles;
  inputs.ripple_motor_cycles = analysis.ripple_motor_cycles;
  inputs.ripple_periods = analysis.ripple_periods;
  inputs.ripple_motor_periods = analysis.ripple_motor_periods;
  // Ripple is periodic in an angle: a prismatic joint (q in m) has no revolution to count over.
  for (int j = 0; j < model.joint_count(); ++j)
    if (model.is_prismatic(j)) inputs.ripple_cycles[j] = inputs.ripple_motor_cycles[j] = 0.0;
  inputs.prediction_rate = analysis.prediction_rate;
  inputs.abs_gravity = setup.abs_gravity ? *setup.abs_gravity : gravity_load(model, s);
  inputs.reference_temperature =
      s.temperature.cols() == s.joints()
          ? s.temperature.col(0).array().isFinite().select(s.temperature.col(0).array(), 0).mean()
          : 25.0;
  inputs.viscous = fit.viscous;
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

/// The part of `theta` outside the friction, which the friction curves are fitted beside.
Eigen::VectorXd non_friction_part(const std::vector<FeatureGroup>& groups,
                                  const Eigen::VectorXd& theta) {
  Eigen::VectorXd part = theta;
  for (const FeatureGroup& g : groups)
    if (g.written_to == WrittenTo::kFriction || g.written_to == WrittenTo::kNothing)
      for (int c : g.columns)
        part[c] = 0.0;
  return part;
}

/// The effort predictions pass 4 needs, in one pass over the samples.
struct EffectPredictions {
  Eigen::MatrixXd selected, declared;  ///< the selected and the declared linear models
  std::vector<Eigen::MatrixXd> terms;  ///< per selected effect, as the written model has it
  Eigen::MatrixXd non_friction;        ///< written, outside the friction (curves fit it)
  Eigen::MatrixXd declared_rigid;      ///< the declared rigid body (its curves fit it)
  Eigen::MatrixXd final_non_friction;  ///< non_friction of the model refitted on every row
};

EffectPredictions predict_effects(const EffectDesign& design, const EffectDiagnosis& d,
                                  const EffectSelection& sel, bool refitted) {
  std::vector<Eigen::VectorXd> thetas{sel.theta_selected, sel.theta_before};
  for (std::size_t e = 0; e < d.selected.size(); ++e) {
    // A written effect's term as the written model holds it; the others as selected.
    const Eigen::VectorXd& from = d.claims[e].written ? sel.theta_written : sel.theta_selected;
    Eigen::VectorXd part = Eigen::VectorXd::Zero(design.features());
    for (int c : d.groups[d.selected[e]].columns)
      part[c] = from[c];
    thetas.push_back(part);
  }
  thetas.push_back(non_friction_part(d.groups, sel.theta_written));
  thetas.push_back(only_family<RigidBodyColumns>(d.groups, sel.theta_declared));
  if (refitted) thetas.push_back(non_friction_part(d.groups, sel.theta_final));
  std::vector<Eigen::MatrixXd> p = design.predict_each(d.samples, thetas);
  EffectPredictions out;
  out.selected = std::move(p[0]);
  out.declared = std::move(p[1]);
  for (std::size_t e = 0; e < d.selected.size(); ++e)
    out.terms.push_back(std::move(p[e + 2]));
  const std::size_t next = d.selected.size() + 2;
  out.non_friction = std::move(p[next]);
  out.declared_rigid = std::move(p[next + 1]);
  if (refitted) out.final_non_friction = std::move(p[next + 2]);
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

/// The declared model as identify fits it: the declared rigid body and friction curves, nothing
/// added.
NominalModelX declared_nominal(const ModelX& model, const EffectDesign& design,
                               const Eigen::VectorXd& theta_declared, const BaseParameters& base,
                               const JointSamples& s,
                               const Eigen::MatrixXd& declared_rigid_prediction,
                               const CandidateInputs& inputs) {
  const LinearNominal fit = linear_nominal(model, design, base, theta_declared);
  NominalModelX declared = fit.nominal;
  declared.friction = fit_friction_curves(s, declared_rigid_prediction, inputs.abs_gravity,
                                          fit.linear, false, 20000)
                          .parameters;
  return declared;
}

/// The written model refitted on every row, held-out ones included (EffectSelection::theta_final,
/// `non_friction` its prediction outside the friction), each joint's friction curve or linear
/// fit as chosen on the held-out rows (`judged`): what the parameter file gets once the
/// selection and the curves are judged.
NominalModelX refitted_on_every_row(const std::vector<FeatureGroup>& groups,
                                    const Eigen::VectorXd& theta_final,
                                    const Eigen::MatrixXd& non_friction, const BaseParameters& base,
                                    const CandidateInputs& inputs, const JointSamples& s,
                                    const ModelX& model, const FrictionCurves& judged) {
  NominalModelX final_model;
  final_model.model = model;
  final_model.resize(model.joint_count());
  final_model.base_count = base.size();
  bool load_selected = false;
  const StribeckParametersX linear =
      write_effects(groups, theta_final, base, inputs, final_model, load_selected);
  final_model.friction = refit_friction_curves(s, non_friction, inputs.abs_gravity, linear,
                                               load_selected, 20000, judged);
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
      model, EffectDesign::regressor_columns(model.joint_count(), base.independent, true), s);
}

}  // namespace

IdentificationSetup prepare_diagnosis(const Log& log, const ModelX& model,
                                      const SampleOptions& options) {
  IdentificationSetup setup = prepare_identification(log, model, options);
  setup.regressors = diagnosis_regressors(model, setup.base, setup.samples);
  setup.abs_gravity = std::make_shared<const Eigen::MatrixXd>(gravity_load(model, setup.samples));
  return setup;
}

Diagnosis diagnose(const Log& log, const ModelX& model, const DiagnoseOptions& options) {
  IdentificationSetup setup = prepare_identification(log, model, options.samples);
  return diagnose(log, model, std::move(setup), options);
}

Diagnosis diagnose(const Log& log, const ModelX& model, IdentificationSetup setup,
                   const DiagnoseOptions& options) {
  require_uncoupled_drives(model, "diagnose");
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
  FitSelection selection;  // fit on moving samples: friction at rest has memory
  selection.regimes = {false, true, true};

  say("diagnose: pass 1/4: declared model");
  const auto regressors =
      setup.regressors ? setup.regressors : diagnosis_regressors(model, setup.base, s);
  const EffectDesign declared(model, setup.base, s, regressors, {}, threshold);
  const RobotFileInertiaPrior declared_prior =
      options.inertia_prior ? robot_file_inertia_prior(model, declared, setup.base)
                            : RobotFileInertiaPrior{};
  const DeclaredFit fit = fit_declared(model, setup.base, declared, s, selection,
                                       options.inertia_prior ? &declared_prior : nullptr,
                                       options.inertia_prior_strength);
  selection.joint_weights = fit.joint_weights;
  out.inertia_prior_strength = fit.prior_strength;
  out.min_mass_eigenvalue_without_prior = fit.min_mass_eigenvalue_without_prior;
  out.inertia_prior_choice = fit.prior_choice;
  if (options.inertia_prior && !(declared_prior.floor > 0))
    out.notes.push_back(
        "inertia prior not applied: the robot file's own M(q) is not positive "
        "definite (smallest eigenvalue " +
        format_number(10 * declared_prior.floor, 4) +
        " kg·m²), so it sets no floor to lift the fit's to");

  say("diagnose: pass 2/4: residual analysis");
  const ResidualAnalysis analysis =
      analyse_residual(s, fit.residual, fit.rigid_prediction, model.gear_ratio,
                       options.samples.acceleration_cutoff_hz);
  out.noise_floor = analysis.noise_floor;
  out.motion_noise = analysis.motion_noise;
  out.model_band_hz = options.samples.acceleration_cutoff_hz;
  out.notes = analysis.notes;
  if (s.temperature.cols() != joints)
    out.notes.push_back("temperature-dependent friction not checked: the log has no temp<j>");
  if (joints == 1) out.notes.push_back("coupling between joints not checked: one joint");

  say("diagnose: pass 3/4: candidate effects");
  const EffectDesign design(model, setup.base, s, regressors,
                            candidate_inputs(model, setup, s, analysis, fit), threshold);
  const CandidateInputs& inputs = design.candidates();  // not copied: |G(q)| of every sample
  const DesignGrams grams = design.accumulate(s);
  if (fit.prior_strength > 0) {  // the declared fit's strength for every fit from here on
    selection.prior = robot_file_prior(model, design, setup.base);
    selection.prior.strength = fit.prior_strength;
  }
  out.groups = design.groups();
  std::vector<TransferFold> transfer;
  std::vector<OutsideFold> outside;
  held_out_folds(log, design, s, transfer, outside);
  EffectSelection sel =
      select_effects(grams, transfer, outside, out.groups, design.declared_columns(), selection,
                     analysis.variance_inflation, options);
  out.trials = std::move(sel.trials);
  out.selected = sel.selected;
  out.claims = sel.claims;
  out.before = sel.before;
  out.after = sel.after;

  say("diagnose: pass 4/4: refit with the selected effects");
  out.refitted = holds_rows_out(s);
  EffectPredictions p = predict_effects(design, out, sel, out.refitted);
  out.residual_after = std::move(p.selected);  // in place: effort − prediction
  out.residual_after = s.effort - out.residual_after;
  out.residual_before = std::move(p.declared);
  out.residual_before = s.effort - out.residual_before;
  out.effect_terms = std::move(p.terms);
  NominalModelX& nominal = out.nominal;
  nominal.model = model;
  nominal.resize(joints);
  nominal.base_count = setup.base.size();
  bool load_selected = false;
  const StribeckParametersX linear =
      write_effects(out.groups, sel.theta_written, setup.base, inputs, nominal, load_selected);
  // The written models on the held-out samples: the extended one (what --params holds) and the
  // declared model as identify fits it: independent fits at once, then both residuals in one
  // pass (one forward kinematics per sample).
  FrictionCurves curves;
  parallel_jobs(2, [&](int job) {
    if (job == 0)
      curves =
          fit_friction_curves(s, p.non_friction, inputs.abs_gravity, linear, load_selected, 20000);
    else
      out.declared = declared_nominal(model, design, sel.theta_declared, setup.base, s,
                                      p.declared_rigid, inputs);
  });
  nominal.friction = curves.parameters;
  for (const std::string& note : curves.notes)
    out.notes.push_back("friction curve: " + note);
  std::vector<Eigen::MatrixXd> residuals = nominal_residuals({&nominal, &out.declared}, s);
  out.residual_written = std::move(residuals[0]);
  parallel_jobs(2, [&](int job) {
    (job == 0 ? out.written_after : out.written_before) =
        split_regime_stats(s, job == 0 ? out.residual_written : residuals[1], true);
  });

  out.judged = out.nominal;
  if (out.refitted)
    out.nominal = refitted_on_every_row(out.groups, sel.theta_final, p.final_non_friction,
                                        setup.base, inputs, s, model, curves);

  out.cad_payload = judge_cad_payload(
      grams, out.groups, cad_rigid_body(model, setup.base, out.groups, design.features()),
      out.selected, transfer, selection, analysis.variance_inflation, options);
  out.findings = diagnosis_findings(out, options);
  return out;
}

}  // namespace tpf::offline
