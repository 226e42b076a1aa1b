// Folder validate/: `tpf validate` only: a saved parameter file scored on other logs, every row
// held out (decide_held_out_rows with all_held_out).
//
// `tpf validate`: a saved model applied to other logs (held out by log), scored per joint and
// regime in the log's effort unit, and against the joint torque sensor where there is one.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/regimes/regime_stats.hpp"
#include "offline/samples/joint_samples.hpp"
#include "tpf/estimation/load_estimator.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::offline {

/// One column of the validation table: what an estimator predicts on every sample of the log.
/// (The nominal model is one; a compensated model is another, built the same way.)
struct EffortEstimate {
  std::string name;  ///< e.g. "nominal model"
  /// Predicted effort [N·m] (samples × joints; NaN where not predicted).
  Eigen::MatrixXd effort;
  /// The part of the drive torque the joint torque sensor does not see, N·m: the gear's friction
  /// and the rotor's inertia, d = friction(q̇, |G(q)|, T) + I_a·q̈ (samples × joints).
  Eigen::MatrixXd drive_loss;
};

/// The current-based joint torque against the torque sensor of one joint, N·m, per regime, over
/// the samples where the sensor varies in its file (torque_sensor.hpp) and the sample is valid.
struct SensorScore {
  std::size_t samples = 0;
  RegimeStats maker;    ///< tau_maker − τ_sensor (the drive maker's own estimate; NaN: absent)
  RegimeStats kt_only;  ///< K_t·i − τ_sensor
  std::vector<RegimeStats> estimates;  ///< per EffortEstimate: K_t·i − d − τ_sensor
  /// [file]: RMSE over all regimes of that file, {maker, Kt only, estimates...} (NaN where the
  /// file's sensor is not usable).
  std::vector<std::vector<double>> by_file;
};

/// The validation of some estimates on one (possibly several-file) log.
struct Validation {
  std::string effort_unit;  ///< of the log: the effort residuals below are in it
  bool simulated = false;
  std::vector<std::string> estimate_names;
  std::vector<std::string> files;  ///< the log's file paths (Log::file_path)
  /// [estimate][joint]: effort − predicted effort per regime (all samples are held out).
  std::vector<std::vector<RegimeStats>> effort;
  /// [estimate][file][joint]: the same over all regimes of each file.
  std::vector<std::vector<std::vector<ResidualStats>>> effort_by_file;
  std::vector<SensorScore> sensor;  ///< [joint]; samples = 0 where no file has a usable sensor
  std::vector<std::string> sensor_notes;  ///< torque_sensor_report lines
  std::vector<std::string> notes;         ///< what was not evaluated and why
};

/// The nominal model's estimate on `samples`, as the run-time estimator evaluates it (every effect
/// the parameter file holds; the loader refuses those it cannot evaluate): effort = rigid +
/// friction, drive_loss = friction + I_a·q̈ with I_a the identified base
/// parameter of column "Ia<j>" (0, and a note, where the identification grouped it with a link
/// inertia).
EffortEstimate nominal_estimate(const NominalModelX& nominal, const JointSamples& samples,
                                std::vector<std::string>& notes);

/// The nominal model with the friction compensator as the run-time estimator runs it (the setup's
/// estimator over `log`, no skin): effort = nominal.effort + τ_TCN, drive_loss = nominal.drive_loss
/// + τ_TCN (the network learns what the nominal model leaves of the
/// drive's effort on contact-free logs). The compensator's output on every row the estimator
/// took (NaN where it skipped one); its domain is not applied.
EffortEstimate compensated_estimate(const EstimatorSetup<Eigen::Dynamic>& setup, const Log& log,
                                    const EffortEstimate& nominal);

/// Scores `estimates` on `samples` of `log` (every sample is held out): effort residual per
/// joint and regime and per file, in the log's unit (mA for a log of currents: samples.units),
/// and against tau_sensor<j> in N·m (the samples' effort: K_t·i for a log in mA).
Validation score_estimates(const Log& log, const JointSamples& samples,
                           const std::vector<EffortEstimate>& estimates);

/// The plain-text table validate prints.
std::string validation_text(const Validation& v);
/// The same numbers as JSON text.
std::string validation_json(const Validation& v);

}  // namespace tpf::offline
