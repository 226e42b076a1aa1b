// How much of a held-out error comes from motion the fitting files never covered: per joint, the
// held-out samples whose q or q̇ lies outside the fitting samples' range, and their share of the
// held-out squared error.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

struct CoverageShare {
  /// Per joint, over the held-out samples with a finite residual: share of them outside the
  /// fitting range, and their share of the residual's sum of squares (NaN: no residual).
  std::vector<double> position_samples, position_error;
  std::vector<double> velocity_samples, velocity_error;
  /// Per joint: the fitting samples' range of q̇ [rad/s] (over those with a finite residual).
  std::vector<double> fit_velocity_min, fit_velocity_max;
};

/// The fitting range of joint j is [min, max] of q (q̇) over `fit`'s samples where `fit_residual`
/// (samples × joints) is finite; `heldout_residual` is the held-out residual whose squared error
/// is attributed.
CoverageShare coverage_share(const JointSamples& fit, const Eigen::MatrixXd& fit_residual,
                             const JointSamples& heldout, const Eigen::MatrixXd& heldout_residual);

}  // namespace tpf::offline
