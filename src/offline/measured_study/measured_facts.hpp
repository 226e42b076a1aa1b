// What a set of measured logs can and cannot decide, computed from the logs themselves: seconds
// per file, velocity reversals and direction per joint, flat sensors, velocity noise at rest, and
// files that repeat another file's motion (the current's run-to-run spread).
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/samples/joint_samples.hpp"
#include "offline/samples/repeated_motion.hpp"

namespace tpf::offline {

struct MeasuredFactsOptions {
  /// A reversal is a change of sign of q̇ between two stretches where |q̇| ≥ this [rad/s].
  double reversal_velocity = 0.01;
  /// "At rest" for the velocity noise: |q̇| below this [rad/s] …
  double rest_velocity = 1e-3;
  /// … of which samples at or above the static threshold are labelled moving by noise [rad/s].
  double static_velocity = 1e-4;
  /// Two files repeat one motion when the RMS of Δq over their common length stays below this on
  /// every joint [rad] (repeated_motions).
  double repeat_tolerance = 0.01;
};

/// One file of the logs.
struct MeasuredFile {
  std::string name;  ///< file name without folders
  double seconds = 0.0;
  Eigen::Index samples = 0;
  std::vector<int> reversals;          ///< per joint
  std::vector<double> positive_share;  ///< per joint: share of |q̇| ≥ reversal_velocity with q̇ > 0
  std::vector<bool> sensor_usable;  ///< per joint (torque_sensor.hpp)
};

struct MeasuredFacts {
  std::vector<MeasuredFile> files;
  /// Per joint, over every file: RMS of q̇ where |q̇| < rest_velocity, and the share of those
  /// samples with |q̇| ≥ static_velocity (labelled moving by the noise alone).
  std::vector<double> rest_velocity_rms, rest_noise_moving_share;
  std::vector<RepeatedMotion> repeats;
  /// Per joint, sample-to-sample noise [N·m] of K_t·i and of τ_sensor (where it varies): the RMS
  /// second difference within each file over √6, the σ of white noise.
  std::vector<double> current_noise, sensor_noise;
  /// Per joint: share of the held-out samples whose q lies outside the fitting files' range of q
  /// (outside_range_share; empty when not computed).
  std::vector<double> outside_share;
  MeasuredFactsOptions options;
};

/// Per joint: the share of `heldout`'s valid samples with q outside [min, max] of `fit`'s q.
std::vector<double> outside_range_share(const JointSamples& fit, const JointSamples& heldout);

/// One log (of one or several files) and its samples.
struct LogWithSamples {
  const Log* log = nullptr;
  const JointSamples* samples = nullptr;
};

/// The facts of every file of `logs` (the samples' effort in N·m; repeated motions are looked
/// for within each log).
MeasuredFacts measured_facts(const std::vector<LogWithSamples>& logs,
                             const MeasuredFactsOptions& options = {});

/// The facts as plain sentences for the report ("opti_traj_testing2: 2.3 s, …").
std::vector<std::string> measured_fact_lines(const MeasuredFacts& facts);

}  // namespace tpf::offline
