// The dynamics is linear in its parameters: τ = Y(q, q̇, q̈) π.
#pragma once

#include <array>

#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// Number of regressor columns for N joints: 10 inertial parameters per link, then armature,
/// Coulomb and viscous friction per joint (Eigen::Dynamic for a run-time joint count).
template <int N>
inline constexpr int regressor_columns = N == Eigen::Dynamic ? Eigen::Dynamic : 13 * N;

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
  const int n = model.joint_count();
  DynamicParameters<S, N> pi(13 * n);
  for (int k = 1; k <= n; ++k)
    pi.template segment<10>(10 * (k - 1)) = model.inertias[k].parameters();
  pi.segment(10 * n, n) = model.armature;
  pi.segment(11 * n, n) = coulomb;
  pi.segment(12 * n, n) = viscous;
  return pi;
}

/// The regressor Y (N × 13N) with Y π = RNEA(q, q̇, q̈) + τ_c sgn(q̇) + b q̇ (friction that the
/// motor must overcome, so measured torque = Y π); where motors are coupled, the armature and
/// friction columns are per motor, Cᵀ·(τ_c,m sgn(θ̇_m) + b_m θ̇_m + I_a,m θ̈_m), θ̇ = C·q̇. Each link's wrench at its origin is linear in
/// its 10 parameters, [f; n] = [F; M] π_k (3 × 10 each, in link k's frame), with
///   f = m a + ω̇ × h + ω × (ω × h),   n = I ω̇ + ω × (I ω) + h × a.
/// A revolute joint j ≤ k carries that wrench's moment about its own origin, z_j · (n + r × f)
/// with r from joint j's origin to link k's, a prismatic one its force z_j · f, so
///   Y(j, π_k) = u_jᵀ M + v_jᵀ F,   u_j = z_j and v_j = z_j × r (prismatic: u_j = 0, v_j = z_j),
///   both in link k's frame,
/// carried up the chain link by link (v ← Rᵀ(v + u × p), u ← Rᵀ u): O(N²) 3-vectors instead of
/// moving every link's 3 × 10 wrench matrices down to each joint. Fills data.oMi as
/// forward_kinematics does. Allocation-free at a fixed N (Y is resized at Eigen::Dynamic).
template <typename S, int N>
void compute_regressor(const Model<S, N>& model, Data<S, N>& data,
                       const NoDeduce<JointVector<S, N>>& q, const NoDeduce<JointVector<S, N>>& dq,
                       const NoDeduce<JointVector<S, N>>& ddq, Regressor<S, N>& Y) {
  forward_kinematics(model, data, q);
  const int n = model.joint_count();
  Y.setZero(n, 13 * n);
  LinkArray<Vector3<S>, N> u, v;  // joint j's axis and z_j × r in the current link's frame
  resize_storage(u, static_cast<std::size_t>(n));
  resize_storage(v, static_cast<std::size_t>(n));
  Vector3<S> w = Vector3<S>::Zero(), dw = Vector3<S>::Zero(), a = -model.gravity;
  for (int k = 1; k <= n; ++k) {
    const Matrix3<S>& R = data.liMi[k].R;
    const Vector3<S>& p = data.liMi[k].p;
    const Vector3<S>& z = model.axes[k - 1];
    const bool prismatic = model.is_prismatic(k - 1);
    Vector3<S> a_k = R.transpose() * (a + dw.cross(p) + w.cross(w.cross(p)));
    const Vector3<S> w_parent = R.transpose() * w;
    if (prismatic) {
      a_k += z * ddq(k - 1) + S(2) * w_parent.cross(z * dq(k - 1));
      w = w_parent;
      dw = R.transpose() * dw;
    } else {
      const Vector3<S> w_k = w_parent + z * dq(k - 1);
      const Vector3<S> dw_k = R.transpose() * dw + z * ddq(k - 1) + w_parent.cross(z * dq(k - 1));
      w = w_k;
      dw = dw_k;
    }
    a = a_k;
    for (int j = 0; j + 1 < k; ++j) {
      v[j] = R.transpose() * (v[j] + u[j].cross(p));
      u[j] = R.transpose() * u[j];
    }
    // A prismatic joint carries the force along its axis: u = 0, v = z.
    u[k - 1] = prismatic ? Vector3<S>::Zero() : z;
    v[k - 1] = prismatic ? z : Vector3<S>::Zero();

    // F = [a | skew(ω̇) + skew(ω)² | 0],  M = [0 | −skew(a) | L(ω̇) + skew(ω) L(ω)], with
    // I x = L(x) [Ixx Ixy Ixz Iyy Iyz Izz]ᵀ.
    const Matrix3<S> F_h = skew(dw) + skew(w) * skew(w);
    const Matrix3<S> M_h = -skew(a);
    Eigen::Matrix<S, 3, 6> M_I;
    M_I << dw.x(), dw.y(), dw.z(), S(0), S(0), S(0),  //
        S(0), dw.x(), S(0), dw.y(), dw.z(), S(0),     //
        S(0), S(0), dw.x(), S(0), dw.y(), dw.z();
    Eigen::Matrix<S, 3, 6> L_w;
    L_w << w.x(), w.y(), w.z(), S(0), S(0), S(0),  //
        S(0), w.x(), S(0), w.y(), w.z(), S(0),     //
        S(0), S(0), w.x(), S(0), w.y(), w.z();
    M_I.noalias() += skew(w) * L_w;

    const int column = 10 * (k - 1);
    for (int j = 0; j < k; ++j) {
      Y(j, column) = v[j].dot(a);
      Y.template block<1, 3>(j, column + 1) = u[j].transpose() * M_h + v[j].transpose() * F_h;
      Y.template block<1, 6>(j, column + 4) = u[j].transpose() * M_I;
    }
  }
  const auto sign = [](const S& x) { return x > S(0) ? S(1) : (x < S(0) ? S(-1) : S(0)); };
  if (!model.coupled) {
    for (int j = 0; j < n; ++j) {
      Y(j, 10 * n + j) = ddq(j);
      Y(j, 11 * n + j) = sign(dq(j));
      Y(j, 12 * n + j) = dq(j);
    }
    return;
  }
  // Motor m's armature and friction act on its own rates (C·q̈)_m, (C·q̇)_m, through C(m, :)ᵀ.
  for (int m = 0; m < n; ++m) {
    const S a = model.motor_rate(m, ddq), v = model.motor_rate(m, dq);
    for (int j = 0; j < n; ++j) {
      Y(j, 10 * n + m) = model.coupling(m, j) * a;
      Y(j, 11 * n + m) = model.coupling(m, j) * sign(v);
      Y(j, 12 * n + m) = model.coupling(m, j) * v;
    }
  }
}

}  // namespace tpf
