// Pass 2 of diagnose: what the declared model's residual (fitted on motion) says before any
// candidate is tried — the noise floor, the ripple periods worth trying, how correlated the
// residual is, and the rate of the prediction (the delay candidate's column).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "offline/diagnose/effort_lag.hpp"
#include "offline/samples/joint_samples.hpp"
#include "offline/signal/periodogram.hpp"

namespace tpf::offline {

struct ResidualAnalysis {
  Eigen::VectorXd noise_floor;  ///< per joint: effort noise at rest, std of Δeffort/√2
  /// Per joint: effort noise in motion, the RMS of the effort above the model's band (effort −
  /// its zero-phase low-pass at the acceleration filter's cutoff) over the moving samples (the
  /// held-out ones where some are, the rows of the moving held-out error); NaN
  /// where the joint never moves or the cutoff is not below the sampling's Nyquist frequency.
  Eigen::VectorXd motion_noise;
  /// Per joint: (1 + ρ)/(1 − ρ), ρ the lag-1 autocorrelation of the residual on motion: the
  /// samples are not independent, which inflates every coefficient's variance by this much.
  Eigen::VectorXd variance_inflation;
  /// Per joint: the position ripple's frequency, periods per output revolution fitted as a real
  /// number (fitted_cycles: sin/cos beside an offset and a slope in q), 0 = none …
  Eigen::VectorXd ripple_cycles;
  /// … and its periods within the joint's range of motion (central 98 % of q): under 1, the
  /// ripple cannot be told from an offset and a spring and its frequency is not named.
  Eigen::VectorXd ripple_periods;
  Eigen::VectorXd ripple_motor_cycles;   ///< the same per motor revolution (θ = |G|·q), 0 = none
  Eigen::VectorXd ripple_motor_periods;  ///< its periods of θ within the range of motion
  EffortLag effort_lag;            ///< the delay candidate's lag and column (search_effort_lag)
  std::vector<std::string> notes;  ///< candidates limited by the data, and why
};

/// `residual` = effort − declared prediction (fitted on motion), `rigid_prediction` its rigid-body
/// part (the delay candidate shifts that, over the lag search_effort_lag finds within ±0.1 s: the
/// friction's own lag at a reversal is memory, not a delay), `gear_ratio` per joint. Output ripple
/// is searched from half a period in the joint's range of motion (and 3 periods/rev) to 64
/// periods/rev, motor ripple from 0.5 to 4.5 periods per motor revolution; one with under one
/// period in the range cannot be told from an offset or a slope (ripple_periods). `model_band_hz`:
/// the acceleration filter's cutoff (SampleOptions::acceleration_cutoff_hz), above which the model
/// predicts nothing (motion_noise).
ResidualAnalysis analyse_residual(const JointSamples& samples, const Eigen::MatrixXd& residual,
                                  const Eigen::MatrixXd& rigid_prediction,
                                  const Eigen::VectorXd& gear_ratio, double model_band_hz);

/// The output ripple `residual` (one joint's, per sample) holds over joint j's moving training
/// samples (at most 20 000 of them, evenly strided): output_ripple up to 64 periods/rev; cycles 0
/// when the joint has 100 such samples or fewer.
OutputRipple joint_output_ripple(const JointSamples& samples, const Eigen::VectorXd& residual,
                                 int j);

}  // namespace tpf::offline
