// The time constant of the causal current low-pass (offline: the current-based joint torque
// against a smooth torque sensor), chosen per joint from the residual K_t·i − d − τ_sensor.
#pragma once

#include <Eigen/Core>
#include <span>

#include "offline/log/log.hpp"
#include "offline/measured_study/sensor_residual.hpp"
#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

enum class LowPassCriterion {
  /// The lowest RMSE over all samples pooled: a file with a large oscillation in its current
  /// (a long filter pays there) chooses for every file. Used on the scored files themselves
  /// (the best any time constant could do: an oracle, not a held-out result).
  kPooled,
  /// The lowest worst-file ratio RMSE_f(τ)/RMSE_f(none) over the files with a residual: the
  /// time constant has to help every file, each file one experiment whatever its length and
  /// noise (what the fitting files choose).
  kWorstFile,
};

struct LowPassChoice {
  Eigen::VectorXd time_constant;  ///< per joint [s]; 0 = none (nothing beats the raw current)
  Eigen::VectorXd
      rmse;  ///< per joint: pooled RMSE [N·m] with that time constant (NaN: no residual)
  Eigen::VectorXd worst_ratio;  ///< per joint: the largest per-file RMSE ratio with it
};

/// `residual` (samples × joints, N·m, NaN where not scored) is K_t·i − d − τ_sensor of some
/// model on `log`'s rows; the low-pass replaces K_t·i (`samples.effort`) by
/// causal_low_pass(t, K_t·i, τ) restarted at each file. Tried: 0 and each of `candidates`.
LowPassChoice choose_current_low_pass(
    const Log& log, const JointSamples& samples, const Eigen::MatrixXd& residual,
    LowPassCriterion criterion, std::span<const double> candidates = kCurrentLowPassTimeConstants);

/// `residual` with joint j's K_t·i low-passed with time constant tau[j] (0: unchanged).
Eigen::MatrixXd low_passed_residual(const Log& log, const JointSamples& samples,
                                    const Eigen::MatrixXd& residual, const Eigen::VectorXd& tau);

}  // namespace tpf::offline
