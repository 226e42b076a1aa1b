// The arm loop's est_* log columns (docs/log-format.md) computed offline: the run-time estimator
// replayed over a recorded log, each cycle's answer written as tpf_arm_loop writes it.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/replay/replay_estimator.hpp"

namespace tpf::offline {

/// est_tau_ext1..N, est_contact, est_pad, est_fx, est_fy, est_fz, est_status, in that order.
std::vector<std::string> estimate_column_names(int joints);

/// True for a column the arm loop writes (a name starting with "est_").
bool is_estimate_column(const std::string& name);

/// Runs `estimator` (reset first) over `samples` in order: one row per sample, the columns of
/// estimate_column_names, as the arm loop records a cycle (examples/arm/estimator_hook.cpp):
/// τ̂_ext = EstimatorOutput::external.torque [N·m], est_contact 1/0, est_pad the most loaded pad
/// in contact (1-based, 0: none), est_f* its contact force in the world frame [N] (0 without a
/// pad), est_status the status bits. A cycle the estimator skipped (non-finite input, stale time)
/// has NaN numbers and its status only.
Eigen::MatrixXd estimate_columns(ReplayEstimator& estimator,
                                 const std::vector<ReplaySample>& samples);

/// `log` with its est_* columns (any it had are dropped) replaced by `estimates` (T × (N + 6),
/// estimate_columns of its rows). Throws tpf::Error naming the log when the row count differs.
Log with_estimate_columns(const Log& log, const Eigen::MatrixXd& estimates);

}  // namespace tpf::offline
