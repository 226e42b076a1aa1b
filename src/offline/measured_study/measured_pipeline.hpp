// Folder measured_study/: the study of the measured Kinova Gen3 logs that tpf demo runs
// (MEASURED): the loop below, the facts the logs can and cannot decide (measured_facts), what the
// sensor residual holds (sensor_candidates, fitted on that residual per joint), the causal
// current low-pass, the noise floor, the coverage of the fitted range and the bound against
// oracles, and their report. It reads identify/, diagnose/ and validate/; tpf validate does not
// read it.
//
// The loop on measured data: the Kinova Gen3 logs (data/real/kinova-gen3), held out by file —
// identify, diagnose and train on the fitting files, score the current-based joint torque against
// the torque sensor on the held-out files, test what the residual holds, and say what the files
// cannot decide. Everything here is MEASURED.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "offline/compensator_training/train_compensator.hpp"
#include "offline/identify/identify.hpp"
#include "offline/measured_study/measured_bound.hpp"
#include "offline/measured_study/measured_facts.hpp"
#include "offline/measured_study/sensor_candidates.hpp"
#include "offline/validate/validation.hpp"

namespace tpf::offline {

/// The data's attribution, shown on every measured result.
inline constexpr const char* kMeasuredLabel =
    "MEASURED — Kinova Gen3 logs, W. Chiha, MIT licence (source: "
    "data/real/kinova-gen3/SOURCE.md)";

/// The forward column of identify's plain fit, without the inertia prior
/// (IdentifyOptions::inertia_prior off): what the prior changes.
inline constexpr const char* kWithoutInertiaPriorColumn =
    "after identification without the inertia prior";

struct MeasuredOptions {
  std::filesystem::path out = "tpf-demo";  ///< gen3.*.params.json, gen3.tcn*.json written here
  std::string robot = "real/kinova-gen3/gen3.robot.json";  ///< data_file names
  std::string logs = "real/kinova-gen3/logs";
  /// Fitting files. diagnose holds out the last one (Trajectory1 repeats RunTrajectory1's
  /// motion, so RecordTrajectory_quadratic, a different motion, is last); identify and train fit
  /// on all of them.
  std::vector<std::string> fitting{"RunTrajectory1.csv.gz", "Trajectory1.csv.gz",
                                   "RecordTrajectory_quadratic.csv.gz"};
  std::vector<std::string> scoring{"opti_traj_testing1.csv.gz", "opti_traj_testing2.csv.gz"};
  bool run_diagnose = true;
  bool run_reverse = true;  ///< also fit on the scoring files and score on the fitting files
  bool run_training = true;
  /// identify's subsample of moving samples per joint for the friction curve (Ceres).
  int friction_samples_per_joint = IdentifyOptions{}.friction_samples_per_joint;
  int training_epochs = 40;  ///< per network (reproducible: an epoch budget)
  int joint_hidden = kPerJointHiddenSmall;
  /// Compensator inputs the networks do not see (CompensatorTrainingOptions::masked_inputs):
  /// q (the held-out files move where the fitting files never went) and τ̂_fric,s (against the
  /// sensor it holds the rigid body's error, not friction).
  std::vector<int> compensator_masked_inputs{kPositionInput, kStaticFrictionInput};
  /// Cut-off [Hz] above which the residual counts as noise a model of the motion cannot reach
  /// (MeasuredFloor).
  double floor_cutoff_hz = 20.0;
  /// Below this [Hz] the residual counts as slow (friction, load): MeasuredBound's bands are
  /// below band_low_hz, up to floor_cutoff_hz, and above.
  double band_low_hz = 2.0;
  std::uint64_t seed = 1;
  int threads = 2;
  /// The measured goal: the current-based joint torque this much closer to the sensor than the
  /// arm maker's own estimate (K_t·i).
  double target_reduction = 0.60;
  /// The compensator's target: this much below the best memoryless model's RMSE.
  double compensator_target = 0.30;
};

/// One column of a measured table: an estimate's RMSE against the sensor on the held-out files.
struct MeasuredColumn {
  std::string name;
  std::vector<double> rmse;  ///< per joint [N·m], NaN where no file's sensor varies
};

/// One split: what was fitted on, what was scored on, and the validation of its estimates.
struct MeasuredSplit {
  std::string fitted_on, scored_on;
  Validation validation;
  std::vector<MeasuredColumn> columns;  ///< maker, Kt only, then each estimate
};

/// Residuals against the sensor on the held-out files for the plots [N·m] (samples × joints).
struct MeasuredTraces {
  Eigen::VectorXd t, file_time;  ///< the joined log's time and each sample's time in its file
  Eigen::MatrixXd dq;
  std::vector<std::string> names;         ///< "Kt only", "after identification", …
  std::vector<Eigen::MatrixXd> residual;  ///< per name
};

/// Per joint, on the held-out files: the best memoryless model, the compensator trained against
/// the sensor, and the error floor set by the current's noise. The floor is the RMS of the best
/// memoryless model's residual K_t·i − d − τ_sensor above cutoff_hz; a model whose output has no
/// content there cannot go below it, so it can beat the best memoryless model by at most
/// 1 − floor/best.
struct MeasuredFloor {
  double cutoff_hz = 0.0;
  double target = 0.0;                   ///< MeasuredOptions::compensator_target
  std::vector<std::string> best_name;    ///< the best memoryless column per joint
  std::vector<double> best_rmse;         ///< its RMSE [N·m] (NaN: no usable sensor)
  std::vector<double> compensator_rmse;  ///< "… + compensator trained against it" (NaN: none)
  /// The same compensator trained on the scored files themselves: a bound, not a result (empty
  /// when no compensator was trained).
  std::vector<double> oracle_compensator_rmse;
  std::vector<double> floor;       ///< RMS of the best model's residual above cutoff_hz
  std::vector<double> model_high;  ///< RMS of that model's drive loss d above cutoff_hz
};

struct MeasuredResult {
  MeasuredSplit forward, reverse;  ///< reverse.columns empty when not run
  std::vector<std::string> diagnosis_findings, diagnosis_notes;
  std::string diagnosis_heldout;  ///< the fitting file diagnose held out
  std::string diagnosis_unseen;   ///< its written effects the sensor comparison cannot see
  /// RMSE of the held-out files' effort (mA) less each model: identify's, then diagnose's written
  /// model without its effects and with each added in turn (the current, where link-side
  /// effects show).
  std::vector<MeasuredColumn> diagnosis_effort;
  std::vector<SensorCandidate> candidates;
  /// Per joint: time constant [s] of the causal current low-pass chosen on the fitting files for
  /// the sensor-fitted model (0: none).
  Eigen::VectorXd low_pass_time_constants;
  Eigen::VectorXd reverse_low_pass_time_constants;  ///< the same, chosen for the reverse split
  MeasuredFacts facts;
  MeasuredFloor floor;
  /// What bounds the sensor-fitted friction's held-out error, per split (reverse: fitted on the
  /// scoring files, scored on the fitting files; computed whether or not run_reverse is set).
  MeasuredBound bound, reverse_bound;
  CompensatorTraining training;         ///< on the current residual (tpf train's target)
  CompensatorTraining sensor_training;  ///< on K_t·i − d − τ_sensor where the sensor varies
  MeasuredTraces traces;
  std::vector<std::string> notes;
  double seconds = 0.0;
};

/// identify (all fitting files) → validate on the scoring files → diagnose (held out by file) and
/// its effects one by one → train the per-joint compensator → validate with it → the sensor-side
/// candidates → the reverse split → what bounds the held-out error on both splits (MeasuredBound)
/// → the facts of every file. `progress` gets one line per stage.
MeasuredResult run_measured(const MeasuredOptions& options,
                            const std::function<void(const std::string&)>& progress = {});

/// Column index of `name` in a split's columns (−1: absent).
int measured_column(const MeasuredSplit& split, const std::string& name);

}  // namespace tpf::offline
