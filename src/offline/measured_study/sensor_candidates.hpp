// What the residual of the current-based joint torque against the torque sensor holds, tested
// held out by file: on the fitting files' residual K_t·i − d − τ_sensor (sensor_residual.hpp; d
// the model's drive loss), first Coulomb + viscous are refitted against the sensor (the base),
// then each candidate effect is fitted on top of the base; each is claimed only where it lowers
// the residual on the held-out files (the base against the model alone, a candidate against the
// base). Every candidate's columns, the base's too, are those of the typed effect registry's
// families (offline/effects/: their fill() on each sample); the lag and the current low-pass
// transform the residual instead (sensor_residual.hpp).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "offline/measured_study/sensor_residual.hpp"

namespace tpf::offline {

struct SensorCandidateOptions {
  double min_gain = 0.05;      ///< claimed when the held-out RMSE falls by at least this share
  double max_lag_s = 0.04;     ///< lags tried: −max … +max
  int max_ripple_cycles = 64;  ///< output-side ripple periods per revolution searched up to
};

/// One candidate on one joint: RMSE [N·m] of the residual before (the base; for the base itself,
/// the model alone) and after, on the fitting files (in-file) and on the held-out files.
struct SensorCandidate {
  std::string key;     ///< friction_refit (the base), current_low_pass, lag, and the effects:
                       ///< offset, kt_error, load_friction, held_friction, ripple_motor,
                       ///< ripple_output, temperature
  std::string title;   ///< what a robot engineer would call it
  int joint = 0;       ///< 0-based
  std::string detail;  ///< the fitted value that matters (lag in ms, periods, coefficients)
  /// The number detail leads with: K_t's scale (kt_error), N·m (offset), N·m per N·m
  /// (load_friction), periods/rev (ripple_output), ms (lag, current_low_pass); NaN: none.
  double value = std::numeric_limits<double>::quiet_NaN();
  /// What it cannot be told from on these files, claimed or not: "offset and spring" for an
  /// output ripple with under one period in the joint's range of motion (its frequency is not
  /// named: OutputRippleColumns' group, indistinct_from_beside); empty: none.
  std::string ambiguous_with;
  double fit_before = 0, fit_after = 0, heldout_before = 0, heldout_after = 0;
  bool supported = false;  ///< held-out RMSE down by ≥ min_gain (and in-file down too)
  double heldout_change() const { return heldout_after / heldout_before - 1.0; }
};

/// Every candidate on every joint whose sensor varies in both sides. `gear_ratio` places the
/// strain-wave gear's ripple (1 and 2 periods per motor revolution); the output ripple's frequency
/// is fitted as a real number on what the base leaves of the fitting side (output_ripple, as
/// diagnose does).
std::vector<SensorCandidate> sensor_candidates(const SensorSide& fit, const SensorSide& heldout,
                                               const Eigen::VectorXd& gear_ratio,
                                               const SensorCandidateOptions& options = {});

}  // namespace tpf::offline
