// Log rows as run-time estimator samples: what the estimator would receive on the robot.
#pragma once

#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "tpf/estimation/estimator_types.hpp"

namespace tpf::offline {

/// One EstimatorSample per log row: t, q<j>, dq<j>, the effort (i<j> in mA, else tau<j> in N·m,
/// see Log::effort_prefix), p<k> in kPa (0 when the log has no pad columns). q̈ is left to the
/// estimator's filter (has_ddq = false), as on the robot. Missing values stay NaN, so the
/// estimator flags and skips those rows. Throws tpf::Error naming the log when it has a joint count
/// other than N or a pad count other than 0 or P.
template <int N, int P>
std::vector<EstimatorSample<double, N, P>> estimator_samples(const Log& log);

}  // namespace tpf::offline
