#include "offline/pipeline/tiago_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "offline/common/data_files.hpp"
#include "offline/common/run_time_types.hpp"
#include "offline/compensator_training/held_out_score.hpp"
#include "offline/diagnose/diagnose.hpp"
#include "offline/identify/identify.hpp"
#include "offline/log/read_logs.hpp"
#include "offline/log/unit_check.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "offline/report/text_format.hpp"
#include "offline/samples/sample_unit_check.hpp"
#include "tpf/common/error.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/estimation/compensator_weight_files.hpp"
#include "tpf/model/load_robot.hpp"
#include "tpf/model/robot_description.hpp"

namespace tpf::offline {
namespace {

using Say = std::function<void(const std::string&)>;

/// Rows [begin, end) of `log` as a log of their own, `what` appended to its source.
Log log_rows(const Log& log, Eigen::Index begin, Eigen::Index end, const std::string& what) {
  Log part = log;
  part.values = log.values.middleRows(begin, end - begin).eval();
  part.file_starts = {0};
  part.source = log.source + " (" + what + ")";
  return part;
}

/// The first row whose time is at least `time` (t.size() when none).
Eigen::Index first_row_at(const Eigen::VectorXd& t, double time) {
  Eigen::Index k = 0;
  while (k < t.size() && t[k] < time)
    ++k;
  return k;
}

/// The replay setup of `nominal` with parameters from the noise of `calibration` (joints that
/// never rest there take the largest noise of those that do).
ReplaySetup setup_of(const NominalModelX& nominal, const Log& calibration) {
  ReplaySetup setup;
  setup.nominal = nominal;
  std::vector<int> never_rests;
  setup.parameters = estimator_parameters_from_noise(
      estimate_sensor_noise(calibration, nominal.model.torque_constant, &never_rests));
  return setup;
}

EstimatorTrace trace_of(const ReplaySetup& setup, const Log& log) {
  return replay_estimator(setup, estimator_samples(log, setup.nominal.model, 0));
}

/// Trains the per-joint networks on the fitted part's first 1 − gate_share, scores them on the
/// rest and writes the gains into the weight files (tpf train's held-out gate); returns the setup
/// with the weights.
ReplaySetup train_with_gate(const TiagoOptions& o, const NominalModelX& nominal, const Log& fit,
                            TiagoResult& r, const Say& say) {
  const Eigen::VectorXd t = fit.col("t");
  const Eigen::Index cut = first_row_at(t, t[0] + (1.0 - o.gate_share) * (t[t.size() - 1] - t[0]));
  r.t_gate = t[cut];
  r.rows_trained = cut, r.rows_gate = fit.rows() - cut;
  ReplaySetup setup = setup_of(nominal, fit);
  CompensatorTrainingOptions options;
  options.per_joint = true;
  options.joint_hidden = o.joint_hidden;
  options.masked_inputs = o.masked_inputs;
  options.tcn.max_epochs = o.training_epochs;
  options.tcn.max_seconds = 0.0;
  options.tcn.threads = o.threads;
  options.tcn.seed = o.seed;
  int last = 0;
  r.training = train_compensator({trace_of(setup, log_rows(fit, 0, cut, "trained rows"))}, options,
                                 [&](const TcnTrainProgress& p) {
                                   if (p.epoch - last < 10 && !p.last) return;
                                   last = p.last ? 0 : p.epoch;
                                   char line[160];
                                   std::snprintf(line, sizeof line,
                                                 "tiago: train: epoch %d, held-out loss %.4g",
                                                 p.epoch, p.validation_loss);
                                   say(line);
                                 });
  const auto path = o.out / "tiago.tcn.json";
  write_compensator(r.training, path);
  const int joints = nominal.model.joint_count();
  setup.weights = find_compensator_weights(path, joints);
  const HeldOutScore score =
      score_held_out({trace_of(setup, log_rows(fit, cut, fit.rows(), "gate rows"))});
  set_held_out_gains(r.training, score);
  write_compensator(r.training, path);
  setup.weights = find_compensator_weights(path, joints);
  const double min_gain = ReplayParameters{}.compensator_min_held_out_gain;
  r.gate = describe_held_out(score, min_gain);
  const std::uint32_t kept = compensated_joints(setup.weights, joints, min_gain);
  for (int j = 0; j < joints; ++j)
    if (kept & (1u << j)) r.compensated_joints.push_back(j + 1);
  return setup;
}

/// RMSE over the finite entries of column j.
std::pair<double, std::size_t> column_rmse(const Eigen::MatrixXd& m, int j) {
  double sum = 0;
  std::size_t n = 0;
  for (Eigen::Index k = 0; k < m.rows(); ++k)
    if (std::isfinite(m(k, j))) sum += m(k, j) * m(k, j), ++n;
  return {n > 0 ? std::sqrt(sum / static_cast<double>(n)) : std::nan(""), n};
}

/// τ [SI] → mA with the robot file's output-side K_t.
Eigen::MatrixXd in_milliamperes(const Eigen::MatrixXd& tau, const Eigen::VectorXd& kt) {
  Eigen::MatrixXd ma = tau;
  for (Eigen::Index j = 0; j < tau.cols(); ++j)
    ma.col(j) *= 1000.0 / kt[j];
  return ma;
}

void score_held_out_part(const TiagoOptions& o, const ReplaySetup& identified,
                         const ReplaySetup& compensated, const Log& held, TiagoResult& r) {
  const Eigen::VectorXd& kt = r.torque_constant;
  const EstimatorTrace id = trace_of(identified, held);
  const EstimatorTrace tr = trace_of(compensated, held);
  const Eigen::MatrixXd nominal = tr.residual;
  const Eigen::MatrixXd network = tr.residual - tr.compensation;
  Eigen::MatrixXd gated = nominal;  // the run time: the network only where the gate keeps it
  for (const int j : r.compensated_joints)
    gated.col(j - 1) = network.col(j - 1);
  for (int j = 0; j < static_cast<int>(kt.size()); ++j) {
    TiagoJointResidual jr;
    jr.identified_si = column_rmse(id.residual, j).first;
    std::tie(jr.nominal_si, jr.rows) = column_rmse(nominal, j);
    jr.compensated_si = column_rmse(network, j).first;
    jr.gated_si = column_rmse(gated, j).first;
    jr.identified_ma = 1000.0 * jr.identified_si / kt[j];
    jr.nominal_ma = 1000.0 * jr.nominal_si / kt[j];
    jr.compensated_ma = 1000.0 * jr.compensated_si / kt[j];
    jr.gated_ma = 1000.0 * jr.gated_si / kt[j];
    r.residual.push_back(jr);
  }
  // Table I in mA; the residuals "meet" within the effort noise (the static band / 3), as the
  // twin's evaluation has it.
  const Eigen::VectorXd meet =
      1000.0 * compensated.parameters.static_dead_band.array() / kt.array() / 3.0;
  r.table = residual_table(
      {{tr.t, tr.dq, in_milliamperes(nominal, kt), in_milliamperes(network, kt)}}, meet);
  r.gated_table = residual_table(
      {{tr.t, tr.dq, in_milliamperes(nominal, kt), in_milliamperes(gated, kt)}}, meet);
  for (const int j : o.table_joints)
    for (const Regime g : {Regime::Static, Regime::StaticToKinetic, Regime::Moving}) {
      const ResidualRow& row = r.row(j, g);
      TiagoGoal goal{j, g, row.nominal.rmse, row.compensated.rmse, 0, 0, row.nominal.count, false};
      goal.change = percent_change(goal.nominal, goal.compensated);
      goal.target = g == Regime::Static            ? -100.0 * o.static_target
                    : g == Regime::StaticToKinetic ? -100.0 * o.transition_target
                                                   : 0.0;
      goal.met = std::isfinite(goal.change) && goal.change <= goal.target;
      r.goals.push_back(goal);
    }
}

void count_events(const TiagoOptions& o, const Log& log, Eigen::Index cut, TiagoResult& r) {
  const Eigen::VectorXd t = log.col("t");
  for (int j = 0; j < static_cast<int>(r.joint_names.size()); ++j) {
    const Eigen::VectorXd dq = log.col(indexed_name("dq", j + 1));
    r.events.push_back({count_motion_events(t, dq, 0, cut, o.reversal_velocity),
                        count_motion_events(t, dq, cut, log.rows(), o.reversal_velocity),
                        count_motion_events(t, dq, 0, r.rows_trained, o.reversal_velocity)});
  }
}

void describe_robot(const ModelX& model, const RobotDescription& robot, TiagoResult& r) {
  for (const DriveDescription& d : robot.drives)
    r.joint_names.push_back(d.joint);
  for (int j = 0; j < model.joint_count(); ++j)
    r.prismatic.push_back(model.is_prismatic(j));
  r.torque_constant = model.torque_constant;
  r.gear_ratio = model.gear_ratio;
}

}  // namespace

const ResidualRow& TiagoResult::row(int joint, Regime regime) const {
  for (const ResidualRow& row : table)
    if (row.joint == joint && row.regime == regime) return row;
  throw Error::at(
      "tiago study", 0, "table",
      "no row for joint " + std::to_string(joint + 1) + ", " + std::string(regime_name(regime)));
}

bool TiagoResult::all_goals_met() const {
  return !goals.empty() &&
         std::all_of(goals.begin(), goals.end(), [](const TiagoGoal& g) { return g.met; });
}

namespace {

void check_options(const TiagoOptions& o) {
  const auto share = [](double v, const char* field) {
    if (!(v > 0.0 && v < 1.0))
      throw Error::at("tiago study", 0, field,
                      "must lie strictly between 0 and 1, is " + format_number(v));
  };
  share(o.fit_share, "fit_share");
  share(o.gate_share, "gate_share");
}

/// identify (written to tiago.identified.params.json, its log checks kept) and diagnose (the
/// nominal model, tiago.nominal.params.json) on the fitted part.
std::pair<NominalModelX, NominalModelX> fit_models(const TiagoOptions& o, const ModelX& model,
                                                   const Log& fit, TiagoResult& r, const Say& say) {
  say("tiago: identify on the first " + format_number(100 * o.fit_share, 3) + " % (t < " +
      format_number(r.t_split, 4) + " s)");
  IdentifyOptions io;
  io.samples.hold_out = false;
  io.friction_samples_per_joint = o.friction_samples_per_joint;
  const Identification identified = identify(fit, model, io);
  save_nominal_model(o.out / "tiago.identified.params.json", identified.nominal, fit.source);
  const LogChecks checks = check_sample_units(model, identified.samples);
  r.dead_joints = checks.dead_joints;
  r.log_problems = checks.problems;
  r.log_notes = checks.notes;
  r.rest_factor = checks.rest_factor;

  say("tiago: diagnose on the fitted part (its own held-out blocks)");
  const Diagnosis diagnosis = diagnose(fit, model);
  r.diagnosis_findings = diagnosis.findings;
  save_nominal_model(o.out / "tiago.nominal.params.json", diagnosis.nominal, fit.source);
  return {identified.nominal, diagnosis.nominal};
}

}  // namespace

TiagoResult run_tiago_study(const TiagoOptions& o, const Say& progress) {
  const auto start = std::chrono::steady_clock::now();
  const auto say = [&](const std::string& line) {
    if (progress) progress(line);
  };
  check_options(o);
  std::filesystem::create_directories(o.out);
  TiagoResult r;
  const std::filesystem::path robot_file = data_file(o.robot);
  const ModelX model = load_robot<double, Eigen::Dynamic>(robot_file);
  describe_robot(model, load_robot_description(robot_file), r);
  const Log log = read_logs(std::vector<std::filesystem::path>{data_file(o.log)});
  if (log.joint_count() != model.joint_count())
    throw Error::at(log.source, 0, "joints",
                    "has " + std::to_string(log.joint_count()) + " joints; the robot file " +
                        robot_file.string() + " has " + std::to_string(model.joint_count()));
  const Eigen::VectorXd t = log.col("t");
  const Eigen::Index cut = first_row_at(t, t[0] + o.fit_share * (t[t.size() - 1] - t[0]));
  r.t_begin = t[0], r.t_split = t[cut], r.t_end = t[t.size() - 1];
  r.rows_fit = cut, r.rows_held_out = log.rows() - cut;
  const Log fit = log_rows(log, 0, cut, "fitted part, t < " + format_number(r.t_split, 4) + " s");
  const Log held =
      log_rows(log, cut, log.rows(), "held-out part, t >= " + format_number(r.t_split, 4) + " s");
  const auto [identified, nominal] = fit_models(o, model, fit, r, say);

  say("tiago: train one network per joint (" + std::to_string(o.training_epochs) +
      " epochs at most), gated on the fitted part's last " + format_number(100 * o.gate_share, 3) +
      " %");
  const ReplaySetup compensated = train_with_gate(o, nominal, fit, r, say);
  count_events(o, log, cut, r);
  if (!o.other_arm_logs.empty())
    r.other_arm = count_file_onsets(data_file(o.other_arm_logs), o.reversal_velocity);
  std::vector<int> never_rests;
  r.noise_ma = 1000.0 *
               estimate_sensor_noise(fit, model.torque_constant, &never_rests).effort.array() /
               model.torque_constant.array();

  say("tiago: validate on the held-out part (t >= " + format_number(r.t_split, 4) + " s)");
  score_held_out_part(o, setup_of(identified, fit), compensated, held, r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace tpf::offline
