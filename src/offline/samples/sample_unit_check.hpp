// A log's units and dead channels checked against the robot file (offline/log/unit_check) on the
// sample table: the robot file's gravity torque at every sample beside the effort.
#pragma once

#include "offline/common/run_time_types.hpp"
#include "offline/log/unit_check.hpp"
#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

/// G_j(q_k) [N·m] per sample k and joint j with the robot file's inertias, wherever the sample's q
/// is finite (the checks read it at the samples missing another value too), NaN elsewhere. Two
/// threads.
Eigen::MatrixXd gravity_torque(const ModelX& model, const JointSamples& samples);

/// The checks of `samples` with the robot file's `model` (what `tpf identify` prints and writes
/// as the fit's "log_checks"). `gravity`: the robot file's G(q) of the samples (gravity_torque)
/// where the caller has it; empty: computed here.
LogChecks check_sample_units(const ModelX& model, const JointSamples& samples,
                             const Eigen::MatrixXd& gravity = {});

}  // namespace tpf::offline
