// The project's 4-joint arm (data/arm4.*): its sizes, the friction networks its estimator runs
// and the weight files they are loaded from. Shared by the offline tools (which train and score
// the estimator) and the run-time loop (examples/arm), so both build the same estimator.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "tpf/estimation/compensator.hpp"
#include "tpf/estimation/estimator_parameters.hpp"
#include "tpf/estimation/estimator_types.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/nn/per_joint_tcn.hpp"
#include "tpf/nn/tcn.hpp"

namespace tpf {

inline constexpr int kArmJoints = 4;
inline constexpr int kArmPads = 11;
using ArmNominal = NominalModel<double, kArmJoints>;
using ArmSample = EstimatorSample<double, kArmJoints, kArmPads>;
using ArmParameters = EstimatorParameters<double, kArmJoints>;
/// Hidden channels and levels of the arm's networks (receptive field 46 samples = 115 ms): one
/// network for all joints has kArmHidden channels; one network per joint has kArmJointHidden (the
/// default, docs/tcn.md "per joint or all joints") or kArmHidden.
inline constexpr int kArmHidden = 32;
inline constexpr int kArmJointHidden = 16;
inline constexpr int kArmLevels = 4;
/// One network for all joints: inputs compensator_input (5N), outputs τ_TCN (N).
using AllJointsTcn =
    Tcn<double, kCompensatorInputsPerJoint * kArmJoints, kArmHidden, kArmLevels, 4, kArmJoints>;
/// One network per joint, Hidden ∈ {kArmJointHidden, kArmHidden}, evaluated in float (trained in
/// double; the float step is ≈ 2× faster, docs/tcn.md "Precision").
template <int Hidden = kArmJointHidden>
using JointTcns = PerJointTcn<double, kArmJoints, Hidden, kArmLevels, float>;
/// Whether per-joint networks of `hidden` channels are compiled in.
constexpr bool is_arm_joint_hidden(int hidden) {
  return hidden == kArmJointHidden || hidden == kArmHidden;
}

/// Which compensator the estimator runs.
enum class CompensatorLayout { None, AllJoints, PerJoint };

/// Per-joint weight file name of joint j (0-based) for `path`: "<dir>/<stem>.joint<j+1>.json".
std::filesystem::path joint_weight_path(const std::filesystem::path& path, int joint);

/// The weight files of a compensator path: `path` itself when it holds an all-joints network
/// (inputs 5N, outputs N), else `<path stem>.joint1.json` … `.joint4.json` (per-joint networks
/// of 5 inputs, 1 output, all of the same hidden size, kArmJointHidden or kArmHidden). Start-up
/// code: throws tpf::Error naming the path when neither exists or a file has the wrong shape.
std::vector<std::string> compensator_files(const std::filesystem::path& path,
                                           CompensatorLayout& layout);

}  // namespace tpf
