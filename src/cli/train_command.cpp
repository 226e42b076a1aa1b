// `tpf train`: the friction compensator (TCN) from contact-free excitation logs and a nominal
// model, with the run-time estimator's own features.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.hpp"
#include "core/common/atomic_file.hpp"
#include "model_file_options.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/compensator_training/held_out_score.hpp"
#include "offline/compensator_training/train_compensator.hpp"
#include "offline/log/read_log.hpp"
#include "offline/log/torque_sensor.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "offline/report/text_table.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"
#include "read_command_logs.hpp"
#include "robot_joint_count.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace {

struct TrainCommandOptions {
  std::vector<std::string> logs;
  tpf::cli::ModelFiles model;
  std::string out;
  std::string checkpoint;
  bool per_joint = false;
  int joint_hidden = tpf::offline::kPerJointHiddenSmall;
  bool quiet = false, verbose = false;
  std::string json;
  double static_to_kinetic_weight =
      tpf::offline::CompensatorTrainingOptions{}.static_to_kinetic_weight;
  double static_weight = tpf::offline::CompensatorTrainingOptions{}.static_weight;
  std::vector<std::string> without;
  tpf::offline::TcnTrainOptions tcn;
};

/// Share of a single log's rows held out (its last time block) when one log is given.
constexpr double kHeldOutShare = 0.2;

/// The logs split into training and held-out data: the last file when several are given and the
/// others hold at least 1 − kHeldOutShare of the rows, else the last kHeldOutShare of the last
/// log's rows (a time block). Says which.
struct SplitLogs {
  std::vector<tpf::offline::Log> training, held_out;
};

SplitLogs split_logs(const TrainCommandOptions& o) {
  using tpf::offline::Log;
  SplitLogs split;
  for (const std::string& path : o.logs)
    split.training.push_back(tpf::cli::read_replayed_log(path, o.quiet));
  Eigen::Index others = 0;  // rows of every file but the last
  for (std::size_t i = 0; i + 1 < split.training.size(); ++i)
    others += split.training[i].rows();
  // By file when the other files hold at least 80 % of the rows (else the last file's last 20 %).
  if (split.training.size() > 1 && double(others) >= (1.0 - kHeldOutShare) / kHeldOutShare *
                                                         double(split.training.back().rows())) {
    split.held_out.push_back(std::move(split.training.back()));
    split.training.pop_back();
    std::printf("train: held out by file: %s (scored, not trained on)\n",
                split.held_out.back().source.c_str());
    return split;
  }
  Log& whole = split.training.back();
  const Eigen::Index rows = whole.rows();
  const Eigen::Index cut = rows - static_cast<Eigen::Index>(kHeldOutShare * double(rows));
  Log tail = whole;
  tail.values = whole.values.bottomRows(rows - cut).eval();
  tail.file_starts = {0};
  tail.source = whole.source + " (last 20 %)";
  whole.values.conservativeResize(cut, Eigen::NoChange);
  const int t = whole.column("t");
  if (t >= 0 && cut > 0 && cut < rows)
    std::printf("train: held out by time: the last 20 %% of %s (t >= %.3f s, %lld of %lld rows)\n",
                whole.source.c_str(), tail.values(0, t), static_cast<long long>(rows - cut),
                static_cast<long long>(rows));
  split.held_out.push_back(std::move(tail));
  return split;
}

/// Says when the log's time steps vary: the networks take its rows as they come (a window spans
/// rows, not seconds), so a jittered clock is read as it is, not resampled.
void say_irregular_steps(const tpf::offline::Log& log) {
  const Eigen::Ref<const Eigen::VectorXd> t = log.col("t");
  if (t.size() < 3) return;
  std::vector<double> steps;
  for (Eigen::Index k = 1; k < t.size(); ++k)
    if (std::isfinite(t[k] - t[k - 1])) steps.push_back(t[k] - t[k - 1]);
  if (steps.empty()) return;
  std::vector<double> sorted = steps;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  std::size_t off = 0;
  for (double d : steps)
    off += std::abs(d - median) > 0.1 * median ? 1 : 0;
  if (off * 100 < steps.size()) return;  // under 1 %: a regular clock
  const auto [lo, hi] = std::minmax_element(steps.begin(), steps.end());
  std::printf(
      "train: %s: %zu of %zu time steps are off the median %.2f ms by more than 10 %% (%.2f-%.2f "
      "ms): the networks take the rows as they come (their window spans rows), not resampled\n",
      log.source.c_str(), off, steps.size(), 1e3 * median, 1e3 * *lo, 1e3 * *hi);
}

/// The estimator's trace over each log (no skin: the network reads no pad; the compensator of
/// `weights`, none by default), with parameters from the log's own noise.
std::vector<tpf::offline::EstimatorTrace> trace_logs(
    const TrainCommandOptions& o, const std::vector<tpf::offline::Log>& logs,
    const tpf::CompensatorWeightFiles& weights = {}) {
  using namespace tpf::offline;
  ReplaySetup setup = tpf::cli::load_model_setup(o.model, "", false);
  const int joints = setup.nominal.model.joint_count();
  setup.weights = weights;
  std::vector<EstimatorTrace> traces;
  for (const Log& log : logs) {
    // Where the torque sensor is flat or missing, as identify and diagnose say it: the sensor is
    // never an input of the networks.
    for (const std::string& line : torque_sensor_problems(log, joints))
      std::printf("%s\n", line.c_str());
    say_irregular_steps(log);
    std::vector<int> never_rests;
    setup.parameters = estimator_parameters_from_noise(
        estimate_sensor_noise(log, setup.nominal.model.torque_constant, &never_rests));
    for (int j : never_rests)
      std::printf(
          "train: %s: joint %d never rests (fewer than 10 consecutive rows with |dq| < 1e-4 "
          "rad/s): its network is trained and scored without the rest regime\n",
          log.source.c_str(), j + 1);
    traces.push_back(replay_estimator(setup, estimator_samples(log, setup.nominal.model, 0)));
  }
  return traces;
}

/// The held-out score as a table: per joint, nominal -> compensated RMSE of each regime, and
/// whether the gate keeps the network.
tpf::offline::Table held_out_table(const tpf::offline::HeldOutScore& score, double min_gain) {
  using tpf::TcnWeightFile;
  tpf::offline::Table table;
  table.header = {"joint"};
  for (const char* regime : TcnWeightFile::kHeldOutRegimes)
    table.header.emplace_back(regime);
  table.header.emplace_back("network");
  for (Eigen::Index j = 0; j < score.gain[0].size(); ++j) {
    std::vector<std::string> row{std::to_string(j + 1)};
    bool kept = true;
    for (std::size_t r = 0; r < 3; ++r) {
      char cell[64] = "not scored";
      const double g = score.gain[r][j];
      if (std::isfinite(g))
        std::snprintf(cell, sizeof cell, "%.3g -> %.3g", score.nominal_rmse[r][j],
                      score.compensated_rmse[r][j]);
      row.emplace_back(cell);
      kept = kept && (!std::isfinite(g) || g >= min_gain);
    }
    row.emplace_back(kept ? "used" : "GATED OFF");
    table.rows.push_back(std::move(row));
  }
  return table;
}

/// Scores the written networks on the held-out logs, writes the gains into the weight files
/// and prints them with the gate's verdict (the estimator's default threshold): a table, with
/// --verbose a line per joint with the change and rows of each regime.
tpf::offline::HeldOutScore score_and_rewrite(const TrainCommandOptions& o,
                                             const std::vector<tpf::offline::Log>& held_out,
                                             tpf::offline::CompensatorTraining& result) {
  using namespace tpf::offline;
  const auto weights =
      tpf::find_compensator_weights(o.out, tpf::cli::robot_joint_count(o.model.robot));
  const HeldOutScore score = score_held_out(trace_logs(o, held_out, weights));
  set_held_out_gains(result, score);
  write_compensator(result, o.out);
  const double min_gain = ReplayParameters{}.compensator_min_held_out_gain;
  std::printf(
      "train: held out, RMSE nominal -> with the network [N*m]; the gate keeps a network whose "
      "gain is >= %.1f %% in every regime scored:\n",
      100.0 * min_gain);
  if (o.verbose) {
    for (const std::string& line : describe_held_out(score, min_gain))
      std::printf("train:   %s\n", line.c_str());
  } else {
    std::printf("%s", table_text(held_out_table(score, min_gain)).c_str());
  }
  return score;
}

/// Refuses weight files (--out, --checkpoint; per joint, each joint's) that would overwrite an
/// input or each other.
void refuse_colliding_outputs(const TrainCommandOptions& o) {
  const int joints = o.per_joint ? tpf::cli::robot_joint_count(o.model.robot) : 1;
  using namespace tpf::cli;
  refuse_overwriting_inputs(
      "train", joined(each_of("--log", o.logs), model_inputs(o.model)),
      joined(joined(written_weight_files("--out", o.out, o.per_joint, joints),
                    written_weight_files("--checkpoint", o.checkpoint, o.per_joint, joints)),
             {{"--json", o.json}}));
}

/// "train: wrote a.joint1.json … a.joint4.json (4 files)"; --verbose: one line per file.
void print_written(const std::vector<std::string>& paths, bool verbose) {
  if (verbose || paths.size() < 3) {
    for (const std::string& p : paths)
      std::printf("train: wrote %s\n", p.c_str());
    return;
  }
  std::printf("train: wrote %s … %s (%zu files)\n", paths.front().c_str(), paths.back().c_str(),
              paths.size());
}

/// Each network's best epoch and held-out loss: one line for all; --verbose: one per network.
void print_networks(const tpf::offline::CompensatorTraining& result, bool verbose) {
  std::string epochs, losses;
  for (std::size_t k = 0; k < result.results.size(); ++k) {
    const tpf::offline::TcnTrainResult& r = result.results[k];
    const char* note = r.stopped_early ? ", stopped early"
                       : r.stopped_on_time
                           ? ", STOPPED BY THE WALL-CLOCK SAFETY NET (--max-seconds): "
                             "not reproducible on another machine"
                           : "";
    if (verbose || r.stopped_on_time)
      std::printf("train: network %zu: best epoch %d of %zu, held-out loss %.4g (N*m^2)%s\n", k + 1,
                  r.best_epoch, r.history.size(), r.best_validation_loss, note);
    char cell[32];
    std::snprintf(cell, sizeof cell, "%s%d/%zu", k == 0 ? "" : " ", r.best_epoch, r.history.size());
    epochs += cell;
    std::snprintf(cell, sizeof cell, "%s%.3g", k == 0 ? "" : " ", r.best_validation_loss);
    losses += cell;
  }
  if (!verbose)
    std::printf("train: best epoch per network %s; held-out loss [N*m^2] %s\n", epochs.c_str(),
                losses.c_str());
  std::printf("train: %zu training / %zu held-out windows, %.1f s\n", result.training_windows,
              result.validation_windows, result.seconds);
}

/// Everything train found, for --json: per network its epochs (loss history) and per joint and
/// regime the held-out RMSE and gain.
nlohmann::json training_json(const tpf::offline::CompensatorTraining& result,
                             const tpf::offline::HeldOutScore& score) {
  using tpf::TcnWeightFile;
  nlohmann::json j;
  j["training_windows"] = result.training_windows;
  j["held_out_windows"] = result.validation_windows;
  j["seconds"] = result.seconds;
  for (const tpf::offline::TcnTrainResult& r : result.results) {
    nlohmann::json n{{"best_epoch", r.best_epoch},
                     {"best_held_out_loss", r.best_validation_loss},
                     {"stopped_early", r.stopped_early},
                     {"stopped_on_time", r.stopped_on_time},
                     {"history", nlohmann::json::array()}};
    for (const auto& e : r.history)
      n["history"].push_back({{"train_loss", e.train_loss}, {"held_out_loss", e.validation_loss}});
    j["networks"].push_back(n);
  }
  const auto number = [](double v) {
    return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
  };
  for (Eigen::Index q = 0; q < score.gain[0].size(); ++q) {
    nlohmann::json joint;
    for (std::size_t r = 0; r < 3; ++r)
      joint[TcnWeightFile::kHeldOutRegimes[r]] = {
          {"nominal_rmse_nm", number(score.nominal_rmse[r][q])},
          {"compensated_rmse_nm", number(score.compensated_rmse[r][q])},
          {"gain", number(score.gain[r][q])},
          {"rows", score.rows[r][q]}};
    j["held_out"].push_back(joint);
  }
  return j;
}

void run_train(TrainCommandOptions o) {
  using namespace tpf::offline;
  const SplitLogs split = split_logs(o);
  const std::vector<EstimatorTrace> traces = trace_logs(o, split.training);
  CompensatorTrainingOptions options;
  options.tcn = o.tcn;
  options.tcn.checkpoint_path = o.checkpoint;
  options.per_joint = o.per_joint;
  options.joint_hidden = o.joint_hidden;
  options.static_to_kinetic_weight = o.static_to_kinetic_weight;
  options.static_weight = o.static_weight;
  for (const std::string& name : o.without)
    options.masked_inputs.push_back(compensator_input_channel(name));
  CompensatorTraining result = train_compensator(
      traces, options,
      o.quiet ? TcnProgressCallback{} : tcn_progress_bar(std::cerr, ::isatty(STDERR_FILENO) == 1));
  print_written(write_compensator(result, o.out), o.verbose);
  print_networks(result, o.verbose);
  const HeldOutScore score = score_and_rewrite(o, split.held_out, result);
  if (!o.json.empty()) {
    tpf::write_file_atomically(o.json, training_json(result, score).dump(1) + "\n");
    std::printf("train: wrote %s\n", o.json.c_str());
  }
}

}  // namespace

namespace tpf::cli {

void register_train_command(CLI::App& app) {
  auto o = std::make_shared<TrainCommandOptions>();
  o->tcn.max_seconds = 0.0;
  o->tcn.min_learning_rate = 5e-5;  // the sixth halving of 2e-3 stops (docs/tcn-training.md)
  CLI::App* cmd = app.add_subcommand(
      "train", "Train the friction compensator (TCN) on contact-free excitation logs");
  cmd->footer(
      "Train the friction compensator (TCN) on contact-free excitation logs: target = effort − "
      "the nominal model's prediction, inputs = what the run-time estimator feeds it"
      "\nExample: tpf train --log ex.csv --params arm4.params.json --per-joint --out "
      "arm4.tcn.json");
  cmd->add_option("--log", o->logs, "Contact-free excitation log(s)")
      ->required()
      ->check(input_file());
  add_model_file_options(cmd, o->model, "Nominal model (tpf-params file from identify/diagnose)",
                         false);
  cmd->add_option("--out", o->out,
                  "Weight file to write (per joint: <stem>.joint<j>.json beside it)")
      ->required();
  cmd->add_flag("--per-joint", o->per_joint, "One network per joint instead of one for all");
  cmd->add_option("--joint-hidden", o->joint_hidden,
                  "Hidden channels of a per-joint network (16 or 32; all joints: 32)")
      ->capture_default_str()
      ->check(one_of({offline::kPerJointHiddenSmall, offline::kPerJointHiddenLarge}));
  cmd->add_option("--seed", o->tcn.seed, "Seed (initialisation, held-out choice, batches)")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_option("--max-epochs", o->tcn.max_epochs,
                  "Epoch budget per network (the reproducible budget; early stopping may end "
                  "sooner)")
      ->capture_default_str()
      ->check(at_least(1));
  cmd->add_option("--max-seconds", o->tcn.max_seconds,
                  "Wall-clock safety net for the whole run (0: none); results then depend on the "
                  "machine's speed")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_option("--epoch-windows", o->tcn.epoch_windows,
                  "At most this many training windows per epoch (0: all); a pass over the "
                  "shuffled windows is split into equal epochs")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_option("--min-learning-rate", o->tcn.min_learning_rate,
                  "Early stopping: stop when the decay would halve the learning rate below this "
                  "(0: never)")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_option("--patience", o->tcn.patience, "Early stopping: epochs without improvement")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_option("--split-cutoff", o->tcn.split_cutoff_hz,
                  "Cut-off of the zero-phase low/high split of the target [Hz]")
      ->capture_default_str()
      ->check(split_cutoff_hz());
  cmd->add_option("--threads", o->tcn.threads, "Worker threads (results do not depend on it)")
      ->capture_default_str()
      ->check(at_least(1));
  cmd->add_option("--checkpoint", o->checkpoint,
                  "Write the best model so far here at each improvement (outputs in N*m)");
  cmd->add_option("--break-away-weight", o->static_to_kinetic_weight,
                  "Loss weight of static-to-kinetic samples (moving samples weigh 1)")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_option("--rest-weight", o->static_weight,
                  "Loss weight of static samples (moving samples weigh 1)")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_option("--without-input", o->without,
                  "A joint input the networks must not see (repeatable): q, dq, ddq, "
                  "static-friction, nominal-friction. Held at 0 in training and removed from the "
                  "written networks, whose output then does not depend on it; e.g. q: friction "
                  "memory independent of where the joint is, for data that do not cover the "
                  "joint's range")
      ->check(CLI::IsMember({"q", "dq", "ddq", "static-friction", "nominal-friction"}));
  cmd->add_flag("--quiet", o->quiet, "No progress bar");
  cmd->add_flag("--verbose", o->verbose,
                "Each file written, each network's epochs, each joint's held-out change and rows");
  cmd->add_option("--json", o->json,
                  "Every network's loss history and the held-out score per joint and regime");
  cmd->callback([o] {
    refuse_colliding_outputs(*o);
    run_train(*o);
  });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
