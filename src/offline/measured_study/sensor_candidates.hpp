// What the residual of the current-based joint torque against the torque sensor holds, tested
// held out by file: on the fitting files' residual K_t·i − d − τ_sensor (d the model's drive
// loss), first Coulomb + viscous are refitted against the sensor (the base), then each candidate
// effect is fitted on top of the base; each is claimed only where it lowers the residual on the
// held-out files (the base against the model alone, a candidate against the base).
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

/// Time constants [s] of the causal current low-pass tried (chosen on the fitting files).
inline constexpr std::array<double, 7> kCurrentLowPassTimeConstants{0.002, 0.005, 0.01, 0.02,
                                                                    0.05,  0.1,   0.2};

/// One side of the split: a log, its samples and a model's drive loss d on them (samples ×
/// joints, N·m; validation.hpp's EffortEstimate::drive_loss).
struct SensorSide {
  const Log* log = nullptr;
  const JointSamples* samples = nullptr;
  Eigen::MatrixXd drive_loss;
};

struct SensorCandidateOptions {
  double min_gain = 0.05;      ///< claimed when the held-out RMSE falls by at least this share
  double max_lag_s = 0.04;     ///< lags tried: −max … +max
  int max_ripple_cycles = 64;  ///< output-side ripple periods per revolution tried
};

/// One candidate on one joint: RMSE [N·m] of the residual before (the base; for the base itself,
/// the model alone) and after, on the fitting files (in-file) and on the held-out files.
struct SensorCandidate {
  std::string key;     ///< offset, kt_error, load_friction, temperature, ripple_motor,
                       ///< ripple_output, held_friction, friction_refit, lag
  std::string title;   ///< what a robot engineer would call it
  int joint = 0;       ///< 0-based
  std::string detail;  ///< the fitted value that matters (lag in ms, periods, coefficients)
  double fit_before = 0, fit_after = 0, heldout_before = 0, heldout_after = 0;
  bool supported = false;  ///< held-out RMSE down by ≥ min_gain (and in-file down too)
  double heldout_change() const { return heldout_after / heldout_before - 1.0; }
};

/// K_t·i − d − τ_sensor per sample and joint [N·m] (the samples' effort is K_t·i), NaN where
/// the sample is invalid or the joint's sensor does not vary in its file.
Eigen::MatrixXd sensor_residual(const SensorSide& side);

/// Every candidate on every joint whose sensor varies in both sides. `gear_ratio` places the
/// strain-wave gear's ripple (1 and 2 periods per motor revolution).
std::vector<SensorCandidate> sensor_candidates(const SensorSide& fit, const SensorSide& heldout,
                                               const Eigen::VectorXd& gear_ratio,
                                               const SensorCandidateOptions& options = {});

}  // namespace tpf::offline
