// Forward dynamics: accelerations from torques.
#pragma once

#include "tpf/dynamics/mass_matrix.hpp"
#include "tpf/dynamics/rnea.hpp"

namespace tpf {

/// q̈ = M(q)⁻¹ (τ − C(q,q̇)q̇ − G(q)), with the armature in M; τ is the total joint torque
/// (motor minus friction plus external). Result in data.ddq. Allocation-free at a fixed N
/// (fixed-size Cholesky).
template <typename S, int N>
const JointVector<S, N>& forward_dynamics(const Model<S, N>& model, Data<S, N>& data,
                                          const NoDeduce<JointVector<S, N>>& q,
                                          const NoDeduce<JointVector<S, N>>& dq,
                                          const NoDeduce<JointVector<S, N>>& tau) {
  compute_mass_matrix(model, data, q);  // also runs joint_transforms
  detail::newton_euler_passes(model, data, dq, JointVector<S, N>::Zero(model.joint_count()).eval(),
                              Vector3<S>(-model.gravity));
  data.mass_factor.compute(data.M);
  data.ddq = data.mass_factor.solve(tau - data.tau);
  return data.ddq;
}

}  // namespace tpf
