// The residual of the current-based joint torque against the torque sensor, K_t·i − d − τ_sensor,
// and the two transformations of it the sensor study tries beside the candidate effects' columns
// (sensor_candidates.hpp): the sensor read later or earlier (a lag), the current low-passed.
#pragma once

#include <Eigen/Core>
#include <array>

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

/// K_t·i − d − τ_sensor per sample and joint [N·m] (the samples' effort is K_t·i), NaN where
/// the sample is invalid or the joint's sensor does not vary in its file.
Eigen::MatrixXd sensor_residual(const SensorSide& side);

/// Joint j's residual r with the sensor read `shift` samples later (within the same file; NaN
/// where either sample's residual is NaN).
Eigen::VectorXd sensor_shifted(const SensorSide& side, const Eigen::VectorXd& r, int j, int shift);

/// Joint j's residual r with the current through causal_low_pass of time constant `tau` [s]
/// (restarted at each file): r + (LP(K_t·i) − K_t·i).
Eigen::VectorXd current_low_passed(const SensorSide& side, const Eigen::VectorXd& r, int j,
                                   double tau);

}  // namespace tpf::offline
