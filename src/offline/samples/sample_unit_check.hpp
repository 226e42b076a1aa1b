// A log's units and dead channels checked against the robot file (offline/log/unit_check) on the
// sample table: the robot file's gravity torque at every sample beside the effort.
#pragma once

#include "offline/common/run_time_types.hpp"
#include "offline/log/unit_check.hpp"
#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

/// The checks of `samples` with the robot file's `model` (what `tpf identify` prints and writes
/// as the fit's "log_checks").
LogChecks check_sample_units(const ModelX& model, const JointSamples& samples);

}  // namespace tpf::offline
