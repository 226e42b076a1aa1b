#include "offline/measured_study/measured_pipeline.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "offline/common/data_files.hpp"
#include "offline/diagnose/diagnose.hpp"
#include "offline/effects/effect_columns.hpp"
#include "offline/identify/identify.hpp"
#include "offline/log/read_logs.hpp"
#include "offline/measured_study/low_pass_choice.hpp"
#include "offline/measured_study/noise_floor.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "offline/report/text_format.hpp"
#include "offline/signal/causal_low_pass.hpp"
#include "tpf/estimation/compensator_weight_files.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::offline {

/// The Kinova Gen3 has 7 joints: the measured loop uses the tools' existing 7-joint instances.
constexpr int kMeasuredJoints = 7;
namespace {

using Gen3Model = NominalModelX;  ///< of the Gen3's 7 joints

/// nominal_estimate of the Gen3's model.
EffortEstimate gen3_nominal_estimate(const Gen3Model& nominal, const JointSamples& samples,
                                     std::vector<std::string>& notes) {
  return nominal_estimate(nominal, samples, notes);
}

Log read_measured_files(const MeasuredOptions& o, const std::vector<std::string>& names) {
  std::vector<std::filesystem::path> paths;
  for (const std::string& n : names)
    paths.push_back(data_file(std::filesystem::path(o.logs) / n));
  return read_logs(paths);
}

std::string joined_file_names(const std::vector<std::string>& names) {
  return joined(names, " + ");
}

/// Samples with nothing held out: the held-out data are other files.
JointSamples samples_without_holdout(const Log& log, const ModelX& model) {
  SampleOptions options;
  options.hold_out = false;
  return extract_joint_samples(log, model.torque_constant, options);
}

Identification identify_on_every_sample(
    const Log& log, const ModelX& model, int friction_samples, bool friction_from_sensor,
    const std::function<void(const std::string&)>& say,
    bool fit_load_friction = IdentifyOptions{}.fit_load_friction,
    bool inertia_prior = IdentifyOptions{}.inertia_prior) {
  IdentifyOptions options;
  options.inertia_prior = inertia_prior;
  options.friction_samples_per_joint = friction_samples;
  options.samples.hold_out = false;
  options.friction_from_sensor = friction_from_sensor;
  options.fit_load_friction = fit_load_friction;
  options.progress = say;
  return identify(log, model, options);
}

/// The columns of a split: maker, Kt only, then each estimate, RMSE over every regime.
std::vector<MeasuredColumn> measured_split_columns(const Validation& v) {
  std::vector<MeasuredColumn> columns{{"maker (tau_maker)", {}}, {"Kt only", {}}};
  for (const std::string& name : v.estimate_names)
    columns.push_back({name, {}});
  for (const SensorScore& s : v.sensor) {
    const bool usable = s.samples > 0;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    columns[0].rmse.push_back(usable ? s.maker.valid.rmse : nan);
    columns[1].rmse.push_back(usable ? s.kt_only.valid.rmse : nan);
    for (std::size_t e = 0; e < s.estimates.size(); ++e)
      columns[e + 2].rmse.push_back(usable ? s.estimates[e].valid.rmse : nan);
  }
  return columns;
}

/// Whether diagnose's claim e is written as a term of its own (a payload is folded into the
/// rigid body: it cannot be taken out again, so it is not added in turn).
bool separable_written_effect(const Diagnosis& d, std::size_t e) {
  return d.claims[e].written &&
         d.groups[static_cast<std::size_t>(d.selected[e])].written_to != WrittenTo::kRigidBody;
}

/// Diagnose's written model with only its first `keep` separable written effects (the later ones
/// removed), and the titles of those effects in selection order.
Gen3Model with_first_diagnosed_effects(const Diagnosis& d, std::size_t keep,
                                       std::vector<std::string>* titles = nullptr) {
  NominalModelX m = d.nominal;
  std::size_t written = 0;
  for (std::size_t e = 0; e < d.claims.size(); ++e) {
    if (!separable_written_effect(d, e)) continue;
    const FeatureGroup& g = d.groups[static_cast<std::size_t>(d.selected[e])];
    if (titles) titles->push_back(g.title);
    if (written++ >= keep) remove_group(g, m);
  }
  return m;
}

/// The titles of the written claims that cannot be taken out (folded into the rigid body).
std::vector<std::string> folded_effects(const Diagnosis& d) {
  std::vector<std::string> folded;
  for (std::size_t e = 0; e < d.claims.size(); ++e)
    if (d.claims[e].written && !separable_written_effect(d, e))
      folded.push_back(d.groups[static_cast<std::size_t>(d.selected[e])].title);
  return folded;
}

/// Per joint: RMSE of the log's effort less the estimate's over the valid samples, in the log's
/// unit (mA for a log of currents).
std::vector<double> effort_rmse_per_joint(const JointSamples& s, const EffortEstimate& e) {
  std::vector<double> out;
  for (int j = 0; j < s.joints(); ++j) {
    double sum = 0, n = 0;
    for (Eigen::Index k = 0; k < s.size(); ++k) {
      const double r = s.effort(k, j) - e.effort(k, j);
      if (s.valid[static_cast<std::size_t>(k)] && std::isfinite(r)) sum += r * r, ++n;
    }
    out.push_back(n > 0 ? s.units.to_effort(j, std::sqrt(sum / n)) : std::nan(""));
  }
  return out;
}

/// Equal values, NaN equal to NaN.
bool same_values_or_nan(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return ((a.array() == b.array()) || (a.array().isNaN() && b.array().isNaN())).all();
}

std::size_t written_effect_count(const Diagnosis& d) {
  std::size_t n = 0;
  for (std::size_t e = 0; e < d.claims.size(); ++e)
    n += separable_written_effect(d, e);
  return n;
}

/// The per-joint compensator trained on the fitting log over `nominal`, as tpf train does: on
/// the current residual τ_res of the run-time estimator, or, where `sensor_target` (samples ×
/// joints, N·m) has a value on the joint, on K_t·i − d − τ_sensor (the drive loss the model
/// misses, as the sensor measures it; NaN rows are cut out of the training windows).
ReplaySetup train_measured_compensator(const MeasuredOptions& o, const Log& fit,
                                       const Gen3Model& nominal,
                                       const Eigen::MatrixXd& sensor_target,
                                       const std::string& weight_file,
                                       CompensatorTraining& training,
                                       const std::function<void(const std::string&)>& say) {
  ReplaySetup setup;
  setup.nominal = nominal;
  setup.parameters =
      estimator_parameters_from_noise(estimate_sensor_noise(fit, nominal.model.torque_constant));
  std::vector<EstimatorTrace> traces{
      replay_estimator(setup, estimator_samples(fit, setup.nominal.model, 0))};
  for (int j = 0; j < static_cast<int>(sensor_target.cols()); ++j)
    if (sensor_target.col(j).array().isFinite().any())
      traces[0].residual.col(j) = sensor_target.col(j);
  CompensatorTrainingOptions options;
  options.per_joint = true;
  options.joint_hidden = o.joint_hidden;
  options.masked_inputs = o.compensator_masked_inputs;
  // Against the sensor the static-friction estimate τ̂_fric,s (τ_res frozen at rest) holds the
  // rigid body's error, not friction: start from a random network, not from predicting it.
  options.start_from_baseline = sensor_target.cols() == 0;
  options.tcn.max_epochs = o.training_epochs;
  options.tcn.max_seconds = 0.0;
  options.tcn.threads = o.threads;
  options.tcn.seed = o.seed;
  int last = 0;
  training = train_compensator(traces, options, [&](const TcnTrainProgress& p) {
    if (p.epoch - last < 10 && !p.last) return;
    last = p.last ? 0 : p.epoch;
    char line[160];
    std::snprintf(line, sizeof line, "measured: train: epoch %d, held-out loss %.4g", p.epoch,
                  p.validation_loss);
    say(line);
  });
  const auto weights = o.out / weight_file;
  write_compensator(training, weights);
  setup.weights = find_compensator_weights(weights, kMeasuredJoints);
  return setup;
}

/// K_t·i − d − τ_sensor of `estimate` (or Kt only when null) on the scoring log.
Eigen::MatrixXd sensor_residual_of(const Log& log, const JointSamples& s,
                                   const EffortEstimate* estimate) {
  SensorSide side{&log, &s,
                  estimate ? estimate->drive_loss : Eigen::MatrixXd::Zero(s.size(), s.joints())};
  return sensor_residual(side);
}

Eigen::VectorXd time_within_file(const Log& log, const JointSamples& s) {
  Eigen::VectorXd t(s.size());
  for (std::size_t f = 0; f < log.file_count(); ++f) {
    const auto [begin, end] = log.file_rows(f);
    for (Eigen::Index k = begin; k < end; ++k)
      t[k] = s.t[k] - s.t[begin];
  }
  return t;
}

/// `e` with the current through causal_low_pass of time constant tau[j] on joint j: the drive
/// loss less (LP(K_t·i) − K_t·i), so that K_t·i − d becomes LP(K_t·i) − d.
EffortEstimate low_passed_estimate(const EffortEstimate& e, const Log& log, const JointSamples& s,
                                   const Eigen::VectorXd& tau) {
  EffortEstimate out = e;
  for (Eigen::Index j = 0; j < tau.size(); ++j) {
    const Eigen::VectorXd effort = s.effort.col(j);
    out.drive_loss.col(j) -= causal_low_pass(s.t, effort, tau[j], log.file_starts) - effort;
  }
  return out;
}

/// Per joint, the time constant (0: none) that minimises the RMSE of `e` against the sensor on
/// the fitting side, pooled (MeasuredBound also reports the worst-file rule, not used here).
Eigen::VectorXd choose_low_pass_time_constants(const Log& log, const JointSamples& s,
                                               const EffortEstimate& e) {
  return choose_current_low_pass(log, s, sensor_residual({&log, &s, e.drive_loss}),
                                 LowPassCriterion::kPooled)
      .time_constant;
}

/// What every stage reads: the arm, the fitting and the scoring logs with their samples.
struct MeasuredData {
  ModelX model;
  Log fit, score;
  JointSamples fit_samples, score_samples;  ///< effort in N·m
};

using Say = std::function<void(const std::string&)>;

/// Stage 1: identify (current-based), identify with the friction against the sensor, and the
/// latter with the current low-passed: estimates 0, 1, 2 on the scoring files.
std::vector<EffortEstimate> identify_stage(const MeasuredOptions& o, MeasuredData& d,
                                           MeasuredResult& result, Gen3Model& identified,
                                           Gen3Model& sensor_model, const Say& say) {
  say("measured: identify on " + joined_file_names(o.fitting));
  identified =
      identify_on_every_sample(d.fit, d.model, o.friction_samples_per_joint, false, say).nominal;
  save_nominal_model(o.out / "gen3.identified.params.json", identified,
                     d.fit.source + " (MEASURED)");
  std::vector<EffortEstimate> estimates{
      gen3_nominal_estimate(identified, d.score_samples, result.notes)};
  estimates.back().name = "after identification";
  say("measured: identify again, the friction fitted against the torque sensor");
  sensor_model =
      identify_on_every_sample(d.fit, d.model, o.friction_samples_per_joint, true, say).nominal;
  save_nominal_model(o.out / "gen3.sensor-friction.params.json", sensor_model,
                     d.fit.source + " (MEASURED)");
  std::vector<std::string> ignored;  // the same notes again
  estimates.push_back(gen3_nominal_estimate(sensor_model, d.score_samples, ignored));
  estimates.back().name = "friction against the sensor";
  const EffortEstimate on_fit = gen3_nominal_estimate(sensor_model, d.fit_samples, ignored);
  result.low_pass_time_constants = choose_low_pass_time_constants(d.fit, d.fit_samples, on_fit);
  estimates.push_back(
      low_passed_estimate(estimates[1], d.score, d.score_samples, result.low_pass_time_constants));
  estimates.back().name = "+ current low-pass";
  return estimates;
}

/// Stage 2: diagnose on the fitting files (held out: the last one); its written model against
/// the sensor, and each written effect in turn against the scoring files' current.
void diagnose_stage(const MeasuredOptions& o, const MeasuredData& d, MeasuredResult& result,
                    std::vector<EffortEstimate>& estimates, const Say& say) {
  say("measured: diagnose on " + joined_file_names(o.fitting) + " (held out: " + o.fitting.back() +
      ")");
  const Diagnosis diagnosis = diagnose(d.fit, d.model, {});
  result.diagnosis_findings = diagnosis.findings;
  result.diagnosis_notes = diagnosis.notes;
  result.diagnosis_heldout = o.fitting.back();
  save_nominal_model(o.out / "gen3.diagnosed.params.json", diagnosis.nominal,
                     d.fit.source + " (MEASURED)");
  std::vector<std::string> titles, unseen, ignored;
  with_first_diagnosed_effects(diagnosis, 0, &titles);
  result.diagnosis_effort.push_back(
      {"after identification", effort_rmse_per_joint(d.score_samples, estimates.front())});
  // A payload folded into the rigid body is scored as the step from diagnose's declared model
  // (fitted without it) to its written model without the separable effects.
  const std::vector<std::string> folded = folded_effects(diagnosis);
  if (!folded.empty())
    result.diagnosis_effort.push_back(
        {"diagnose's declared model (as identify fits it, nothing added)",
         effort_rmse_per_joint(d.score_samples, gen3_nominal_estimate(diagnosis.declared,
                                                                      d.score_samples, ignored))});
  for (std::size_t keep = 0; keep <= written_effect_count(diagnosis); ++keep) {
    EffortEstimate e = gen3_nominal_estimate(with_first_diagnosed_effects(diagnosis, keep),
                                             d.score_samples, ignored);
    const std::string name = keep > 0 ? "+ " + titles[keep - 1]
                             : folded.empty()
                                 ? "diagnose's model without its effects"
                                 : "+ " + joined(folded, ", ") + " (folded into the rigid body)";
    result.diagnosis_effort.push_back({name, effort_rmse_per_joint(d.score_samples, e)});
    if (keep > 0 && same_values_or_nan(e.drive_loss, estimates.back().drive_loss)) {
      unseen.push_back(titles[keep - 1]);
      continue;
    }
    e.name = keep == 0 ? "diagnose's model" : "diagnose: + " + titles[keep - 1];
    estimates.push_back(std::move(e));
  }
  if (!unseen.empty())
    result.diagnosis_unseen =
        "diagnose's " + joined_file_names(unseen) +
        " act on the link side (validate counts only friction and armature as the drive loss "
        "d that the sensor behind the gear does not see): K_t·i − d − τ_sensor is the same "
        "with or without them, so they get no column of their own.";
}

/// Stage 3: the per-joint compensators on the fitting files, scored through validate's path:
/// over the identified model on the current residual, and over the sensor-fitted friction
/// against the sensor.
void compensator_stage(const MeasuredOptions& o, const MeasuredData& d, MeasuredResult& result,
                       const Gen3Model& identified, const Gen3Model& sensor_model,
                       std::vector<EffortEstimate>& estimates, const Say& say) {
  say("measured: train one network per joint on " + joined_file_names(o.fitting) + " (" +
      std::to_string(o.training_epochs) + " epochs at most), on the current residual");
  const ReplaySetup setup =
      train_measured_compensator(o, d.fit, identified, {}, "gen3.tcn.json", result.training, say);
  estimates.push_back(compensated_estimate(setup, d.score, estimates[0]));
  estimates.back().name = "with the compensator";
  say("measured: the same networks over the sensor-fitted friction, trained against the "
      "torque sensor (K_t·i − d − τ_sensor)");
  std::vector<std::string> ignored;
  const SensorSide fit_side{&d.fit, &d.fit_samples,
                            gen3_nominal_estimate(sensor_model, d.fit_samples, ignored).drive_loss};
  const ReplaySetup sensor_setup =
      train_measured_compensator(o, d.fit, sensor_model, sensor_residual(fit_side),
                                 "gen3.tcn-sensor.json", result.sensor_training, say);
  estimates.push_back(compensated_estimate(sensor_setup, d.score, estimates[1]));
  estimates.back().name = "friction against the sensor + compensator trained against it";
}

/// Stage 4: identify without the inertia prior (IdentifyOptions::inertia_prior off: the plain
/// fit, whose M(q) on the fitting files is not positive definite), scored on the scoring files as
/// the last column: what the prior changes. The memoryless floor below leaves it out.
void plain_fit_stage(const MeasuredOptions& o, const MeasuredData& d,
                     std::vector<EffortEstimate>& estimates, const Say& say) {
  say("measured: identify again without the inertia prior (--no-inertia-prior), the plain fit");
  const bool from_sensor = false, fit_load_friction = true, inertia_prior = false;
  const Identification id =
      identify_on_every_sample(d.fit, d.model, o.friction_samples_per_joint, from_sensor, say,
                               fit_load_friction, inertia_prior);
  save_nominal_model(o.out / "gen3.no-inertia-prior.params.json", id.nominal,
                     d.fit.source + " (MEASURED)");
  std::vector<std::string> ignored;  // the same notes again
  estimates.push_back(gen3_nominal_estimate(id.nominal, d.score_samples, ignored));
  estimates.back().name = kWithoutInertiaPriorColumn;
}

/// A bound, not a result: the compensator trained against the sensor as compensator_stage does,
/// but on the scored files themselves (it sees what it is scored on), over the sensor-fitted
/// friction (`sensor_estimate` on the scored files). RMSE against the sensor per joint [N·m]
/// (NaN where no sensor moves).
std::vector<double> oracle_compensator_rmse(const MeasuredOptions& o, const MeasuredData& d,
                                            const Gen3Model& sensor_model,
                                            const EffortEstimate& sensor_estimate, const Say& say) {
  say("measured: oracle: the same networks trained on " + joined_file_names(o.scoring) +
      " themselves (a bound for the compensator target)");
  const SensorSide side{&d.score, &d.score_samples, sensor_estimate.drive_loss};
  CompensatorTraining training;
  const ReplaySetup setup =
      train_measured_compensator(o, d.score, sensor_model, sensor_residual(side),
                                 "gen3.tcn-sensor-oracle.json", training, say);
  const Validation v = score_estimates(d.score, d.score_samples,
                                       {compensated_estimate(setup, d.score, sensor_estimate)});
  std::vector<double> rmse;
  for (const SensorScore& s : v.sensor)
    rmse.push_back(s.samples > 0 ? s.estimates[0].valid.rmse
                                 : std::numeric_limits<double>::quiet_NaN());
  return rmse;
}

/// The plots' residuals on the scoring files: Kt only, after identification, the sensor-fitted
/// friction with the low-pass, and (when trained) the compensator trained against the sensor.
MeasuredTraces plot_traces(const MeasuredData& d, const std::vector<EffortEstimate>& estimates,
                           bool trained) {
  MeasuredTraces tr;
  tr.t = d.score_samples.t;
  tr.file_time = time_within_file(d.score, d.score_samples);
  tr.dq = d.score_samples.dq;
  const auto add = [&](const std::string& name, const EffortEstimate* e) {
    tr.names.push_back(name);
    tr.residual.push_back(sensor_residual_of(d.score, d.score_samples, e));
  };
  add("Kt only", nullptr);
  add("after identification", &estimates[0]);
  add("friction against the sensor + current low-pass", &estimates[2]);
  if (trained)
    add("friction against the sensor + compensator trained against it", &estimates.back());
  return tr;
}

/// Stage 6: the other way round, fitted on the scoring files and scored on the fitting files.
MeasuredSplit reverse_stage(const MeasuredOptions& o, const MeasuredData& d,
                            Eigen::VectorXd& time_constants, Gen3Model& sensor_model,
                            const Say& say) {
  say("measured: reverse split: identify on " + joined_file_names(o.scoring) + ", score on " +
      joined_file_names(o.fitting));
  std::vector<std::string> notes;
  std::vector<EffortEstimate> estimates;
  for (bool from_sensor : {false, true}) {
    const Gen3Model model =
        identify_on_every_sample(d.score, d.model, o.friction_samples_per_joint, from_sensor, say)
            .nominal;
    estimates.push_back(gen3_nominal_estimate(model, d.fit_samples, notes));
    estimates.back().name = from_sensor ? "friction against the sensor" : "after identification";
    if (from_sensor) sensor_model = model;
  }
  // The low-pass chosen on this split's fitting files (the scoring files of the forward one).
  time_constants = choose_low_pass_time_constants(
      d.score, d.score_samples, gen3_nominal_estimate(sensor_model, d.score_samples, notes));
  estimates.push_back(low_passed_estimate(estimates[1], d.fit, d.fit_samples, time_constants));
  estimates.back().name = "+ current low-pass";
  MeasuredSplit split;
  split.fitted_on = joined_file_names(o.scoring);
  split.scored_on = joined_file_names(o.fitting);
  split.validation = score_estimates(d.fit, d.fit_samples, estimates);
  split.columns = measured_split_columns(split.validation);
  return split;
}

/// Names of the memoryless models among the forward columns (no compensator, no current filter).
constexpr std::array<const char*, 3> kMemorylessColumns{
    "after identification", "friction against the sensor", "diagnose's model"};
constexpr const char* kSensorCompensatorColumn =
    "friction against the sensor + compensator trained against it";

/// The best memoryless model per joint on the scoring files and the floor of its residual.
MeasuredFloor measured_floor(const MeasuredData& d, const MeasuredSplit& split,
                             const std::vector<EffortEstimate>& estimates, double cutoff_hz,
                             double target) {
  MeasuredFloor f;
  f.cutoff_hz = cutoff_hz;
  f.target = target;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const int compensator = measured_column(split, kSensorCompensatorColumn);
  for (std::size_t j = 0; j < split.validation.sensor.size(); ++j) {
    int best = -1;
    for (const char* name : kMemorylessColumns) {
      const int c = measured_column(split, name);
      if (c >= 0 && std::isfinite(split.columns[c].rmse[j]) &&
          (best < 0 || split.columns[c].rmse[j] < split.columns[best].rmse[j]))
        best = c;
    }
    f.best_name.push_back(best < 0 ? "" : split.columns[best].name);
    f.best_rmse.push_back(best < 0 ? nan : split.columns[best].rmse[j]);
    f.compensator_rmse.push_back(compensator < 0 ? nan : split.columns[compensator].rmse[j]);
    if (best < 0) {
      f.floor.push_back(nan);
      f.model_high.push_back(nan);
      continue;
    }
    // Columns 0, 1 are the maker and Kt only; estimate e is column e + 2.
    const EffortEstimate& e = estimates[static_cast<std::size_t>(best - 2)];
    const Eigen::MatrixXd r = sensor_residual_of(d.score, d.score_samples, &e).col(j);
    const Eigen::MatrixXd loss = e.drive_loss.col(static_cast<Eigen::Index>(j));
    f.floor.push_back(high_frequency_rms(d.score, d.score_samples.t, r, cutoff_hz)[0]);
    f.model_high.push_back(high_frequency_rms(d.score, d.score_samples.t, loss, cutoff_hz)[0]);
  }
  return f;
}

/// Stage 7: what bounds the sensor-fitted friction's held-out error on both splits; `fitted` was
/// identified on the fitting files, `scored_fitted` on the scoring files.
void bound_stage(const MeasuredOptions& o, const MeasuredData& d, const Gen3Model& fitted,
                 const Gen3Model& scored_fitted, MeasuredResult& result) {
  std::vector<std::string> ignored;
  const EffortEstimate on_fit = gen3_nominal_estimate(fitted, d.fit_samples, ignored);
  const EffortEstimate on_score = gen3_nominal_estimate(fitted, d.score_samples, ignored);
  const EffortEstimate own_score = gen3_nominal_estimate(scored_fitted, d.score_samples, ignored);
  const EffortEstimate own_fit = gen3_nominal_estimate(scored_fitted, d.fit_samples, ignored);
  const MeasuredBoundSide fit{&d.fit, &d.fit_samples}, score{&d.score, &d.score_samples};
  result.bound = measured_bound(fit, score, on_fit, on_score, own_score, o.target_reduction,
                                o.band_low_hz, o.floor_cutoff_hz);
  // The load terms of the friction (α_c, α_v on |G_j(q)|, the load the run time has) left out.
  const Say quiet;
  const auto without_load = [&](const Log& log, const JointSamples& on) {
    return gen3_nominal_estimate(
        identify_on_every_sample(log, d.model, o.friction_samples_per_joint, true, quiet, false)
            .nominal,
        on, ignored);
  };
  result.bound.fitted_on = joined_file_names(o.fitting);
  result.bound.scored_on = joined_file_names(o.scoring);
  result.reverse_bound = measured_bound(score, fit, own_score, own_fit, on_fit, o.target_reduction,
                                        o.band_low_hz, o.floor_cutoff_hz);
  result.reverse_bound.fitted_on = result.bound.scored_on;
  result.reverse_bound.scored_on = result.bound.fitted_on;
  result.bound.heldout_without_load =
      heldout_sensor_rmse(score, without_load(d.fit, d.score_samples));
  result.reverse_bound.heldout_without_load =
      heldout_sensor_rmse(fit, without_load(d.score, d.fit_samples));
}

}  // namespace

int measured_column(const MeasuredSplit& split, const std::string& name) {
  for (std::size_t c = 0; c < split.columns.size(); ++c)
    if (split.columns[c].name == name) return static_cast<int>(c);
  return -1;
}

MeasuredResult run_measured(const MeasuredOptions& o,
                            const std::function<void(const std::string&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  const Say say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  std::filesystem::create_directories(o.out);
  MeasuredResult result;
  MeasuredData d{load_robot<double, Eigen::Dynamic>(data_file(o.robot)),
                 read_measured_files(o, o.fitting),
                 read_measured_files(o, o.scoring),
                 {},
                 {}};
  d.fit_samples = samples_without_holdout(d.fit, d.model);
  d.score_samples = samples_without_holdout(d.score, d.model);

  Gen3Model identified, sensor_model;
  std::vector<EffortEstimate> estimates =
      identify_stage(o, d, result, identified, sensor_model, say);
  if (o.run_diagnose) diagnose_stage(o, d, result, estimates, say);
  if (o.run_training) compensator_stage(o, d, result, identified, sensor_model, estimates, say);
  plain_fit_stage(o, d, estimates, say);
  say("measured: score on " + joined_file_names(o.scoring) + " against the torque sensor");
  result.forward.fitted_on = joined_file_names(o.fitting);
  result.forward.scored_on = joined_file_names(o.scoring);
  result.forward.validation = score_estimates(d.score, d.score_samples, estimates);
  result.forward.validation.notes = result.notes;
  result.forward.columns = measured_split_columns(result.forward.validation);
  result.floor =
      measured_floor(d, result.forward, estimates, o.floor_cutoff_hz, o.compensator_target);
  if (o.run_training)
    result.floor.oracle_compensator_rmse =
        oracle_compensator_rmse(o, d, sensor_model, estimates[1], say);

  // What the residual holds: each candidate fitted on the fitting files, scored held out.
  say("measured: candidate effects against the torque sensor, held out by file");
  std::vector<std::string> ignored;
  const SensorSide fit_side{&d.fit, &d.fit_samples,
                            gen3_nominal_estimate(identified, d.fit_samples, ignored).drive_loss};
  const SensorSide held_side{&d.score, &d.score_samples, estimates.front().drive_loss};
  result.candidates = sensor_candidates(fit_side, held_side, Eigen::VectorXd(d.model.gear_ratio));
  result.traces = plot_traces(d, estimates, o.run_training);
  Gen3Model scored_sensor_model;
  if (o.run_reverse)
    result.reverse =
        reverse_stage(o, d, result.reverse_low_pass_time_constants, scored_sensor_model, say);
  else
    scored_sensor_model =
        identify_on_every_sample(d.score, d.model, o.friction_samples_per_joint, true, say).nominal;
  say("measured: what bounds the held-out error (oracles, bands, coverage; both splits)");
  bound_stage(o, d, sensor_model, scored_sensor_model, result);
  result.facts = measured_facts({{&d.fit, &d.fit_samples}, {&d.score, &d.score_samples}});
  result.facts.outside_share = outside_range_share(d.fit_samples, d.score_samples);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace tpf::offline
