// The loop on a second measured arm that logs motor currents and no torque sensor: the TIAGo's
// identification log (data/real/tiago), held out by time — identify, diagnose and train on the
// first part, then replay the run-time estimator on the last part and score the current residual
// per joint and regime (Table I, mA, nominal against compensated). Everything here is MEASURED.
#pragma once

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "offline/compensator_training/train_compensator.hpp"
#include "offline/evaluate/residual_table.hpp"
#include "offline/regimes/file_onsets.hpp"
#include "offline/regimes/motion_events.hpp"

namespace tpf::offline {

/// The data's attribution, shown on every TIAGo result.
inline constexpr const char* kTiagoLabel =
    "MEASURED — PAL Robotics TIAGo identification log, T. Nguyen (FIGAROH), Apache-2.0 (source: "
    "data/real/tiago/SOURCE.md)";

struct TiagoOptions {
  std::filesystem::path out = "tpf-demo";  ///< tiago.*.params.json, tiago.tcn*.json written here
  std::string robot = "real/tiago/tiago.robot.json";  ///< data_file names
  std::string log = "real/tiago/logs/tiago.csv.gz";
  /// The first fit_share of the log's time span is fitted on, the rest held out. 0.6 leaves
  /// 4–5 reversals and 6–10 starts per scored joint in the held-out 32 s (0.7 leaves 2 reversals).
  double fit_share = 0.6;
  /// Of the fitted part, the last share is the trainer's own held-out data (the gate the weight
  /// files carry, as tpf train holds out the last 20 % of one log); the networks train on the
  /// rest. On this log those rows (38.5–48.1 s) never rest: the gate scores the moving regime.
  double gate_share = 0.2;
  /// Inputs the networks do not see (CompensatorTrainingOptions::masked_inputs): q, since the
  /// held-out part moves where the fitted part never went (as for the Kinova's held-out files).
  std::vector<int> masked_inputs{kPositionInput};
  /// Table I's joints (0-based): the torso and arm 1–4 (arm 5–7 log all-but-dead currents).
  std::vector<int> table_joints{0, 1, 2, 3, 4};
  /// Reversals count sign changes of q̇ beyond this [rad/s or m/s] (count_motion_events).
  double reversal_velocity = 0.01;
  /// The Kinova Gen3's logs (data_file name; empty: none): their onsets are counted the same
  /// way, to say why Table I is scored on the TIAGo and not there.
  std::string other_arm_logs = "real/kinova-gen3/logs";
  int training_epochs = 40;  ///< per network (reproducible: an epoch budget)
  int joint_hidden = kPerJointHiddenSmall;
  int friction_samples_per_joint = 2000;  ///< identify's Ceres subsample per joint
  std::uint64_t seed = 1;
  int threads = 2;
  /// The goals against the nominal model, per joint: static and static-to-kinetic RMSE this much
  /// lower; no regime higher.
  double static_target = 0.50;
  double transition_target = 0.30;
};

/// One joint's motion events in each part.
struct TiagoEvents {
  MotionEvents fit, held_out;
  MotionEvents trained;  ///< of `fit`, those in the rows the networks trained on (before the gate)
};

/// One joint's current residual on the held-out part over every valid row.
struct TiagoJointResidual {
  /// RMSE [mA]: identify's model, the nominal model (diagnose's), nominal less the network's
  /// output (τ_res − τ_TCN, Table I's "compensated"), and the run time with the gate (compensated
  /// where the gate keeps the network, nominal elsewhere).
  double identified_ma = 0, nominal_ma = 0, compensated_ma = 0, gated_ma = 0;
  /// The same in the effort's SI unit (N·m; N at the prismatic torso): mA/1000 · K_t, with K_t
  /// the robot file's output-side constant, the motor's K_t times the gear ratio.
  double identified_si = 0, nominal_si = 0, compensated_si = 0, gated_si = 0;
  std::size_t rows = 0;
};

/// One (joint, regime) cell of the goal check.
struct TiagoGoal {
  int joint = 0;  ///< 0-based
  Regime regime = Regime::Static;
  double nominal = 0, compensated = 0;  ///< RMSE [mA]
  double change = 0;                    ///< percent_change(nominal, compensated)
  double target = 0;                    ///< percent; 0: not above the nominal model
  std::size_t rows = 0;
  bool met = false;
};

struct TiagoResult {
  std::vector<std::string> joint_names;
  std::vector<bool> prismatic;
  Eigen::VectorXd torque_constant, gear_ratio;  ///< robot file: output side, per joint
  double t_begin = 0, t_split = 0, t_end = 0;   ///< [s]
  Eigen::Index rows_fit = 0, rows_held_out = 0;
  Eigen::Index rows_trained = 0, rows_gate = 0;  ///< the fitted part split for the trainer
  double t_gate = 0;                             ///< the gate's rows from here [s]
  std::vector<int> dead_joints;                  ///< 1-based (identify's log checks)
  std::vector<std::string> log_problems, log_notes;
  std::vector<double> rest_factor;  ///< identify's effort at rest / gravity (NaN: not checked)
  std::vector<std::string> diagnosis_findings;
  std::vector<std::string> gate;        ///< describe_held_out: the trainer's gate per joint
  std::vector<int> compensated_joints;  ///< 1-based: networks the gate keeps
  CompensatorTraining training;
  std::vector<TiagoEvents> events;           ///< per joint
  std::vector<TiagoJointResidual> residual;  ///< per joint
  /// Table I: residual_table on the held-out part [mA], τ_res against τ_res − τ_TCN (as the
  /// twin's evaluation has it: each network's output, whatever the gate).
  std::vector<ResidualRow> table;
  /// The same for the run time with the gate (a gated-off joint keeps τ_res).
  std::vector<ResidualRow> gated_table;
  Eigen::VectorXd noise_ma;           ///< effort noise at rest per joint, fitted part [mA]
  std::vector<TiagoGoal> goals;       ///< table_joints × 3 regimes
  std::vector<FileOnsets> other_arm;  ///< TiagoOptions::other_arm_logs, per file
  std::vector<std::string> notes;
  double seconds = 0.0;

  /// The Table I row of (joint, regime); throws tpf::Error when absent.
  const ResidualRow& row(int joint, Regime regime) const;
  bool all_goals_met() const;
};

/// Reads the log and robot file, splits the log by time, identifies (identify) and diagnoses
/// (diagnose: the nominal model) on the fitted part, trains the per-joint compensator on its
/// first 1 − gate_share and scores it on the rest (the gate the weight files carry), then replays
/// the estimator on the held-out part: residual per joint (identified, nominal, compensated) and
/// Table I per joint and regime. Writes tiago.identified.params.json, tiago.nominal.params.json
/// and tiago.tcn.json (tiago.tcn.joint<j>.json) into options.out.
TiagoResult run_tiago_study(const TiagoOptions& options,
                            const std::function<void(const std::string&)>& progress = {});

}  // namespace tpf::offline
