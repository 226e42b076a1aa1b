// What a memoryless added effect is a function of at one instant: the motion (q, q̇, q̈) and the
// drive ratios that turn a joint angle into a motor angle.
#pragma once

#include "tpf/common/types.hpp"

namespace tpf {

/// The arguments of an added effect's basis functions and torque (references: no copies on the
/// per-cycle path). Angles in rad (output side), rates in rad/s, rad/s².
template <typename S, int N>
struct EffectInput {
  const JointVector<S, N>& q;
  const JointVector<S, N>& dq;
  const JointVector<S, N>& ddq;
  const JointVector<S, N>& gear_ratio;  ///< motor angle = gear_ratio·q (Model::gear_ratio)
};

}  // namespace tpf
