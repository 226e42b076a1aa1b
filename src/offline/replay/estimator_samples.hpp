// Log rows as run-time estimator samples: what the estimator would receive on the robot.
#pragma once

#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "tpf/estimation/estimator_types.hpp"
#include "tpf/model/model.hpp"

namespace tpf::offline {

/// One sample of an N-joint log with its pads (any count, Eigen::Dynamic).
template <int N>
using ReplaySample = EstimatorSample<double, N, Eigen::Dynamic>;

}  // namespace tpf::offline

namespace tpf::offline {

/// One sample per log row for an estimator of N joints and `pads` pads (the layout's count, 0: no
/// skin): t, q<j>, dq<j>, the effort in N·m (i<j> in mA through torque_from_current with the
/// torque constants of `model`, else tau<j> in N·m, see Log::effort_prefix),
/// p<k> in kPa (0 when the log has no pad columns; not read when `pads` is 0). q̈ is left to the
/// estimator's filter (has_ddq = false), as on the robot. Missing values stay NaN, so the estimator
/// flags and skips those rows. Throws tpf::Error naming the log when it has a joint count other
/// than N or a pad count other than 0 or `pads` (`pads` > 0). Compiled for N = 1 … kMaxJoints.
template <int N>
std::vector<ReplaySample<N>> estimator_samples(const Log& log, const Model<double, N>& model,
                                               int pads);

}  // namespace tpf::offline
