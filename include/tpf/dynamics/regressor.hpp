// The dynamics is linear in its parameters: τ = Y(q, q̇, q̈) π.
#pragma once

#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// Number of regressor columns for N joints: 10 inertial parameters per link, then armature,
/// Coulomb and viscous friction per joint.
template <int N>
inline constexpr int regressor_columns = 13 * N;

template <typename S, int N>
using Regressor = Eigen::Matrix<S, N, regressor_columns<N>>;
template <typename S, int N>
using DynamicParameters = Eigen::Matrix<S, regressor_columns<N>, 1>;

/// The parameter vector π that goes with the regressor:
/// [π_link1 … π_linkN (Inertia::parameters(), I about the link origin) | armature (N) |
///  Coulomb τ_c (N) | viscous b (N)], friction entries from the arguments.
template <typename S, int N>
DynamicParameters<S, N> dynamic_parameters(const Model<S, N>& model,
                                           const NoDeduce<JointVector<S, N>>& coulomb,
                                           const NoDeduce<JointVector<S, N>>& viscous) {
  DynamicParameters<S, N> pi;
  for (int k = 1; k <= N; ++k)
    pi.template segment<10>(10 * (k - 1)) = model.inertias[k].parameters();
  pi.template segment<N>(10 * N) = model.armature;
  pi.template segment<N>(11 * N) = coulomb;
  pi.template segment<N>(12 * N) = viscous;
  return pi;
}

/// The regressor Y (N × 13N) with Y π = RNEA(q, q̇, q̈) + τ_c sgn(q̇) + b q̇ (friction that the
/// motor must overcome, so measured torque = Y π). Each link's wrench at its origin is linear in
/// its 10 parameters, [f; n] = A(ω, ω̇, a) π_k, with
///   f = m a + ω̇ × h + ω × (ω × h),   n = I ω̇ + ω × (I ω) + h × a,
/// and is carried down the chain to every joint j ≤ k: Y(j, π_k) = z_j · n_j. Allocation-free.
template <typename S, int N>
void compute_regressor(const Model<S, N>& model, Data<S, N>& data,
                       const NoDeduce<JointVector<S, N>>& q, const NoDeduce<JointVector<S, N>>& dq,
                       const NoDeduce<JointVector<S, N>>& ddq, Regressor<S, N>& Y) {
  forward_kinematics(model, data, q);
  Y.setZero();
  Vector3<S> w = Vector3<S>::Zero(), dw = Vector3<S>::Zero(), a = -model.gravity;
  for (int k = 1; k <= N; ++k) {
    const Matrix3<S>& R = data.liMi[k].R;
    const Vector3<S>& p = data.liMi[k].p;
    const Vector3<S>& z = model.axes[k - 1];
    const Vector3<S> a_k = R.transpose() * (a + dw.cross(p) + w.cross(w.cross(p)));
    const Vector3<S> w_parent = R.transpose() * w;
    const Vector3<S> w_k = w_parent + z * dq(k - 1);
    const Vector3<S> dw_k = R.transpose() * dw + z * ddq(k - 1) + w_parent.cross(z * dq(k - 1));
    w = w_k;
    dw = dw_k;
    a = a_k;

    // I x = L(x) [Ixx Ixy Ixz Iyy Iyz Izz]ᵀ
    auto L = [](const NoDeduce<Vector3<S>>& x) {
      Eigen::Matrix<S, 3, 6> l;
      l << x.x(), x.y(), x.z(), S(0), S(0), S(0),  //
          S(0), x.x(), S(0), x.y(), x.z(), S(0),   //
          S(0), S(0), x.x(), S(0), x.y(), x.z();
      return l;
    };
    Eigen::Matrix<S, 3, 10> F = Eigen::Matrix<S, 3, 10>::Zero();
    Eigen::Matrix<S, 3, 10> M = Eigen::Matrix<S, 3, 10>::Zero();
    F.col(0) = a;
    F.template middleCols<3>(1) = skew(dw) + skew(w) * skew(w);
    M.template middleCols<3>(1) = -skew(a);
    M.template rightCols<6>() = L(dw) + skew(w) * L(w);

    for (int j = k; j >= 1; --j) {
      Y.template block<1, 10>(j - 1, 10 * (k - 1)) = model.axes[j - 1].transpose() * M;
      if (j > 1) {
        const Matrix3<S>& Rj = data.liMi[j].R;
        M = Rj * M + skew(data.liMi[j].p) * Rj * F;
        F = Rj * F;
      }
    }
  }
  for (int j = 0; j < N; ++j) {
    Y(j, 10 * N + j) = ddq(j);
    Y(j, 11 * N + j) = dq(j) > S(0) ? S(1) : (dq(j) < S(0) ? S(-1) : S(0));
    Y(j, 12 * N + j) = dq(j);
  }
}

}  // namespace tpf
