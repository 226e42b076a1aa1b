// Log rows as run-time estimator samples: what the estimator would receive on the robot.
#pragma once

#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "tpf/estimation/estimator_types.hpp"
#include "tpf/model/model.hpp"

namespace tpf::offline {

/// One sample of a log, its joint and pad counts those of the log (Eigen::Dynamic both).
using ReplaySample = EstimatorSample<double, Eigen::Dynamic, Eigen::Dynamic>;

/// One sample per log row for an estimator of `model`'s joints and `pads` pads (the layout's
/// count, 0: no skin): t, q<j>, dq<j>, the effort in N·m (i<j> in mA through torque_from_current
/// with the torque constants of `model`, else tau<j> in N·m, see Log::effort_prefix),
/// p<k> in kPa (0 when the log has no pad columns; not read when `pads` is 0). q̈ is left to the
/// estimator's filter (has_ddq = false), as on the robot. Missing values stay NaN, so the estimator
/// flags and skips those rows. Throws tpf::Error naming the log when it has a joint count other
/// than the model's or a pad count other than 0 or `pads` (`pads` > 0).
std::vector<ReplaySample> estimator_samples(const Log& log,
                                            const Model<double, Eigen::Dynamic>& model, int pads);

}  // namespace tpf::offline
