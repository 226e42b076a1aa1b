// The Coriolis matrix C(q, q̇) with C + Cᵀ = Ṁ.
#pragma once

#include "tpf/dynamics/rnea.hpp"

namespace tpf {

/// The Coriolis matrix built from the Christoffel symbols of M, so that C q̇ is the velocity
/// torque and Ṁ − 2C is skew (C + Cᵀ = Ṁ), as momentum observers need. The velocity torque
/// c(v) = RNEA(q, v, 0) − G is a quadratic form in v, c_i(v) = Σ Γ_ijk v_j v_k with Γ symmetric in
/// (j, k); polarisation gives column j of C: C e_j = ½[c(e_j + q̇) − c(e_j) − c(q̇)].
/// 2N + 1 velocity passes. Result in data.C. Allocation-free.
template <typename S, int N>
const JointMatrix<S, N>& compute_coriolis_matrix(const Model<S, N>& model, Data<S, N>& data,
                                                 const NoDeduce<JointVector<S, N>>& q,
                                                 const NoDeduce<JointVector<S, N>>& dq) {
  forward_kinematics(model, data, q);
  const int n = model.joint_count();
  const JointVector<S, N> zero = JointVector<S, N>::Zero(n);
  const Vector3<S> no_gravity = Vector3<S>::Zero();
  detail::newton_euler_passes(model, data, dq, zero, no_gravity);
  const JointVector<S, N> c_dq = data.tau;
  for (int j = 0; j < n; ++j) {
    JointVector<S, N> v = JointVector<S, N>::Unit(n, j);
    detail::newton_euler_passes(model, data, v, zero, no_gravity);
    const JointVector<S, N> c_e = data.tau;
    v += dq;
    detail::newton_euler_passes(model, data, v, zero, no_gravity);
    data.C.col(j) = S(0.5) * (data.tau - c_e - c_dq);
  }
  return data.C;
}

/// Cᵀ(q, q̇) q̇, the term a generalized-momentum observer needs (p = M q̇, ṗ = τ + Cᵀq̇ − G + τ_ext).
template <typename S, int N>
JointVector<S, N> coriolis_transpose_times_velocity(const Model<S, N>& model, Data<S, N>& data,
                                                    const NoDeduce<JointVector<S, N>>& q,
                                                    const NoDeduce<JointVector<S, N>>& dq) {
  compute_coriolis_matrix(model, data, q, dq);
  return data.C.transpose() * dq;
}

}  // namespace tpf
