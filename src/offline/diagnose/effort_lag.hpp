// The lag between the effort and the motion, searched on the declared model's residual: the
// delay candidate's column is the prediction's difference quotient over that lag, so a delay of
// tens of samples is one column (a derivative fits a lag of a few samples only).
#pragma once

#include <Eigen/Core>

#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

struct EffortLag {
  double lag_s = 0.0;      ///< the effort lags the prediction by this (s; negative: it leads)
  double explained = 0.0;  ///< share of the moving residual's energy the column removes, summed
                           ///< over joints (each joint's share in [0, 1])
  /// (p(t) − p(t − lag))/lag per sample and joint (p: the prediction), 0 where p(t − lag) is
  /// outside the sample's contiguous stretch; the effort e(t) = p(t − d) is p(t) − d·column at
  /// lag = d.
  Eigen::MatrixXd column;
};

/// The lag in whole median steps within ±max_lag_s (at least ±3 steps) whose column removes most
/// of `residual`'s energy on the moving training samples (each joint's share, summed; at most
/// 20 000 samples per joint, evenly strided), `prediction` the declared model's per sample and
/// joint (NaN where it has none).
EffortLag search_effort_lag(const JointSamples& s, const Eigen::MatrixXd& prediction,
                            const Eigen::MatrixXd& residual, double max_lag_s);

}  // namespace tpf::offline
