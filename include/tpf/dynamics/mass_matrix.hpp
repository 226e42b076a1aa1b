// Joint-space inertia matrix by the composite-rigid-body algorithm.
#pragma once

#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

namespace detail {

/// compute_mass_matrix on the joint transforms in data.liMi; joint types tested only when
/// kPrismatic.
template <bool kPrismatic, typename S, int N>
[[gnu::flatten]] void composite_rigid_bodies(const Model<S, N>& model, Data<S, N>& data) noexcept {
  const ModelConstants<S, N>& c = model.constants;
  const int last = model.joint_count();
  data.composite_first_moment[last] = c.first_moment[last];
  data.composite_inertia[last] = c.inertia_about_origin[last];
  for (int k = last - 1; k >= 1; --k) {
    const Matrix3<S>& R = data.liMi[k + 1].R;
    const Vector3<S>& p = data.liMi[k + 1].p;
    const S m = c.subtree_mass[k + 1];
    const Vector3<S> h = R * data.composite_first_moment[k + 1];
    const Vector3<S> v = S(0.5) * m * p + h;
    // R I Rᵀ, 2(p·v)·1 − p vᵀ − v pᵀ and I_o are symmetric: the lower triangle, then mirrored.
    const Matrix3<S> RI = R * data.composite_inertia[k + 1];
    const Matrix3<S>& Io = c.inertia_about_origin[k];
    const S pv2 = S(2) * p.dot(v);
    Matrix3<S>& I = data.composite_inertia[k];
    for (int col = 0; col < 3; ++col)
      for (int row = col; row < 3; ++row) {
        const S rir = RI(row, 0) * R(col, 0) + RI(row, 1) * R(col, 1) + RI(row, 2) * R(col, 2);
        I(row, col) =
            rir + Io(row, col) + (row == col ? pv2 : S(0)) - p[row] * v[col] - v[row] * p[col];
      }
    I(0, 1) = I(1, 0);
    I(0, 2) = I(2, 0);
    I(1, 2) = I(2, 1);
    data.composite_first_moment[k] = c.first_moment[k] + m * p + h;
  }
  const auto prismatic = [&](int k) {
    return kPrismatic && model.joint_types[k - 1] == JointType::prismatic;
  };
  for (int i = last; i >= 1; --i) {
    const Vector3<S>& z = model.axes[i - 1];
    Vector3<S> f, n;
    if (prismatic(i)) {
      f = c.subtree_mass[i] * z;
      n = data.composite_first_moment[i].cross(z);
      data.M(i - 1, i - 1) = z.dot(f) + (model.coupled ? S(0) : model.armature(i - 1));
    } else {
      f = z.cross(data.composite_first_moment[i]);
      n = data.composite_inertia[i] * z;
      data.M(i - 1, i - 1) = z.dot(n) + (model.coupled ? S(0) : model.armature(i - 1));
    }
    for (int j = i - 1; j >= 1; --j) {
      const Matrix3<S>& R = data.liMi[j + 1].R;
      n = R * n + data.liMi[j + 1].p.cross(R * f);
      f = R * f;
      data.M(j - 1, i - 1) = data.M(i - 1, j - 1) = model.axes[j - 1].dot(prismatic(j) ? f : n);
    }
  }
}

/// M += Cᵀ·diag(armature)·C: the rotors of coupled motors.
template <typename S, int N>
void add_coupled_armature(const Model<S, N>& model, Data<S, N>& data) noexcept {
  const int n = model.joint_count();
  for (int m = 0; m < n; ++m)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        data.M(i, j) += model.armature(m) * model.coupling(m, i) * model.coupling(m, j);
}

}  // namespace detail

/// M(q) (N×N, symmetric positive definite) in data.M, armature on the diagonal (through the
/// coupling, Cᵀ·diag(armature)·C, where motors are coupled):
/// kinetic energy T = ½ q̇ᵀ M q̇. Composite bodies k..N are accumulated from the tip (mass, a model
/// constant; first moment h and inertia I about link k's origin): with the child's moved into
/// link k's frame, h' = R h_{k+1}, and v = ½ m_{k+1} p + h',
///   h_k = h_{o,k} + m_{k+1} p + h',  I_k = I_{o,k} + R I_{k+1} Rᵀ + 2(p·v)·1 − p vᵀ − v pᵀ
/// (the parallel-axis theorem for a body whose centre of mass is not at its origin). Column i is
/// the wrench z_i × h_i, I_i z_i that a unit q̈_i demands of composite body i (m_i z_i, h_i × z_i
/// for a prismatic joint), carried down to each joint j ≤ i: M_ji = z_j · n_j (z_j · f_j for a
/// prismatic joint j). Runs joint_transforms (data.liMi at q; data.oMi is left as
/// it was: forward_kinematics gives the link poses). Allocation-free.
template <typename S, int N>
const JointMatrix<S, N>& compute_mass_matrix(const Model<S, N>& model, Data<S, N>& data,
                                             const NoDeduce<JointVector<S, N>>& q) noexcept {
  joint_transforms(model, data, q);
  if (model.constants.has_prismatic)
    detail::out_of_line([&] { detail::composite_rigid_bodies<true>(model, data); });
  else
    detail::composite_rigid_bodies<false>(model, data);
  if (model.coupled) detail::add_coupled_armature(model, data);
  return data.M;
}

}  // namespace tpf
