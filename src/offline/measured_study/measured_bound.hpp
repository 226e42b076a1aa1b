// What bounds the current-based joint torque's held-out error on one split of the measured files
// (MEASURED): the held-out model against oracles that are allowed to see the scored files (the
// same model class fitted on them; the current low-pass with the time constant best on them),
// the residual's frequency bands, the current's content the sensor does not show, and the share
// of the error from motion the fitting files never covered.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/samples/joint_samples.hpp"
#include "offline/validate/validation.hpp"

namespace tpf::offline {

/// Per joint (NaN where the sensor is not scored), RMSE in N·m against the torque sensor on the
/// scored files.
struct MeasuredBound {
  std::string fitted_on, scored_on;
  double low_hz = 0.0, high_hz = 0.0;  ///< the band edges
  std::vector<double> maker, target;   ///< K_t·i alone; (1 − target reduction)·maker
  std::vector<double> heldout;         ///< the sensor-fitted friction, fitted on the fitting files
  /// The same fitted without its load terms (α_c = α_v = 0; empty when not computed).
  std::vector<double> heldout_without_load;
  Eigen::VectorXd fit_time_constants;    ///< the low-pass chosen on the fitting files [s], pooled
  std::vector<double> heldout_low_pass;  ///< + that low-pass (the pipeline's column)
  /// The same with the time constant chosen by LowPassCriterion::kWorstFile on the fitting files
  /// (reported, not used: see docs/measured-data.md).
  Eigen::VectorXd worst_file_time_constants;
  std::vector<double> heldout_worst_file;
  /// Oracles (allowed to see the scored files; not results): the low-pass time constant best on
  /// the scored files over the held-out model; the same model class fitted on the scored files
  /// (in-sample); and both.
  Eigen::VectorXd oracle_time_constants, in_sample_time_constants;
  std::vector<double> oracle_low_pass, in_sample, in_sample_low_pass;
  /// The held-out model's residual K_t·i − d − τ_sensor below low_hz, between, above high_hz.
  std::vector<double> band_low, band_mid, band_high;
  std::vector<double> in_sample_band_low;  ///< the in-sample oracle's residual below low_hz
  /// K_t·i and τ_sensor between low_hz and high_hz on the scored samples: what the current
  /// carries there and the published sensor does not.
  std::vector<double> current_mid, sensor_mid;
  /// Held-out samples outside the fitting samples' range of q̇ and of q: their share of the
  /// samples and of the held-out model's squared error.
  std::vector<double> velocity_samples, velocity_error, position_samples, position_error;
  std::vector<double> fit_velocity_min, fit_velocity_max;  ///< [rad/s]
  /// For the figure: q̇ and K_t·i − τ_sensor (the drive loss the sensor sees, rotor included)
  /// on the fitting and the scored samples, and the held-out model's d on the scored samples.
  Eigen::MatrixXd fit_dq, fit_loss, scored_dq, scored_loss, model_loss;
};

/// One side of a split for measured_bound: a log, its samples (effort K_t·i in N·m), and the
/// sensor-fitted model's estimate on it.
struct MeasuredBoundSide {
  const Log* log = nullptr;
  const JointSamples* samples = nullptr;
};

/// Per joint: RMSE of K_t·i − d − τ_sensor of `estimate` on `side` (NaN where not scored).
std::vector<double> heldout_sensor_rmse(const MeasuredBoundSide& side,
                                        const EffortEstimate& estimate);

/// `heldout` is the model fitted on `fit` scored on `scored`; `in_sample` the same model class
/// fitted on `scored` and scored there; `fit_estimate` the held-out model on `fit` (to choose the
/// fitting files' low-pass as the pipeline does).
MeasuredBound measured_bound(const MeasuredBoundSide& fit, const MeasuredBoundSide& scored,
                             const EffortEstimate& fit_estimate, const EffortEstimate& heldout,
                             const EffortEstimate& in_sample, double target_reduction,
                             double low_hz, double high_hz);

}  // namespace tpf::offline
