// Joint-space inertia matrix by the composite-rigid-body algorithm.
#pragma once

#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// M(q) (N×N, symmetric positive definite) in data.M, armature on the diagonal:
/// kinetic energy T = ½ q̇ᵀ M q̇. Composite bodies k..N are accumulated from the tip (mass,
/// first moment h and inertia I about link k's origin); column i is the wrench z_i × h_i, I_i z_i
/// that a unit q̈_i demands of composite body i, carried down to each joint j ≤ i:
/// M_ji = z_j · n_j. Runs forward_kinematics. Allocation-free.
template <typename S, int N>
const JointMatrix<S, N>& compute_mass_matrix(const Model<S, N>& model, Data<S, N>& data,
                                             const NoDeduce<JointVector<S, N>>& q) {
  forward_kinematics(model, data, q);
  for (int k = N; k >= 1; --k) {
    const Inertia<S>& body = model.inertias[k];
    data.composite_mass[k] = body.mass;
    data.composite_first_moment[k] = body.first_moment();
    data.composite_inertia[k] = body.about_origin();
    if (k < N) {
      const Matrix3<S>& R = data.liMi[k + 1].R;
      const Vector3<S>& p = data.liMi[k + 1].p;
      const S m = data.composite_mass[k + 1];
      const Vector3<S> h = R * data.composite_first_moment[k + 1];
      const Matrix3<S> P = skew(p), H = skew(h);
      data.composite_mass[k] += m;
      data.composite_first_moment[k] += m * p + h;
      data.composite_inertia[k] +=
          R * data.composite_inertia[k + 1] * R.transpose() - m * P * P - P * H - H * P;
    }
  }
  for (int i = N; i >= 1; --i) {
    const Vector3<S>& z = model.axes[i - 1];
    Vector3<S> f = z.cross(data.composite_first_moment[i]);
    Vector3<S> n = data.composite_inertia[i] * z;
    data.M(i - 1, i - 1) = z.dot(n) + model.armature(i - 1);
    for (int j = i - 1; j >= 1; --j) {
      const Matrix3<S>& R = data.liMi[j + 1].R;
      n = R * n + data.liMi[j + 1].p.cross(R * f);
      f = R * f;
      data.M(j - 1, i - 1) = data.M(i - 1, j - 1) = model.axes[j - 1].dot(n);
    }
  }
  return data.M;
}

}  // namespace tpf
