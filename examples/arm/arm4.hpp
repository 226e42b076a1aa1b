// The project's 4-joint arm (data/arm4.*) as the arm loop runs it: everything arm-specific about
// its estimator is this joint count, pad count and compensator, named as types; the rest is data.
#pragma once

#include "tpf/estimation/load_estimator.hpp"

namespace tpf::arm {

inline constexpr int kArmJoints = 4;
inline constexpr int kArmPads = 11;
/// One 16-channel network per joint, evaluated in float (what `tpf train --per-joint` writes).
using ArmEstimator = EstimatorOf<kArmJoints, kArmPads, PerJointTcn<BFloat16Weights, 16>>;
/// The same arm before a compensator is trained (--weights none).
using UncompensatedArmEstimator = EstimatorOf<kArmJoints, kArmPads, NoCompensator>;

}  // namespace tpf::arm
