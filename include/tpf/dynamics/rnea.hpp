// Inverse dynamics by the recursive Newton–Euler algorithm, with armature.
#pragma once

#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf {
namespace detail {

/// The backward Newton–Euler pass on the link forces f_k and moments n_k (link frames, about the
/// link origin) in data.force/data.moment: f_k += R_{k+1} f_{k+1},
/// n_k += R_{k+1} n_{k+1} + p_{k+1} × R_{k+1} f_{k+1}, then τ_k = z_k·n_k. Shared by every form
/// of the inverse dynamics (standard inertias here, linear link parameters in estimation).
template <typename S, int N>
void newton_euler_backward_pass(const Model<S, N>& model, Data<S, N>& data,
                                JointVector<S, N>& tau) noexcept {
  for (int k = N; k >= 1; --k) {
    if (k < N) {
      const Matrix3<S>& R = data.liMi[k + 1].R;
      const Vector3<S> f_child = R * data.force[k + 1];
      data.force[k] += f_child;
      data.moment[k] += R * data.moment[k + 1] + data.liMi[k + 1].p.cross(f_child);
    }
    tau(k - 1) = model.axes[k - 1].dot(data.moment[k]);
  }
}

/// The two Newton–Euler passes on the link transforms already in data.liMi, with base linear
/// acceleration a0 (−g for the full dynamics, 0 for velocity terms only). Writes data.tau without
/// the armature term. Link quantities are in link frames.
template <typename S, int N>
void newton_euler_passes(const Model<S, N>& model, Data<S, N>& data,
                         const NoDeduce<JointVector<S, N>>& dq,
                         const NoDeduce<JointVector<S, N>>& ddq, const NoDeduce<Vector3<S>>& a0) {
  data.omega[0].setZero();
  data.domega[0].setZero();
  data.acc[0] = a0;
  for (int k = 1; k <= N; ++k) {
    const Matrix3<S>& R = data.liMi[k].R;
    const Vector3<S>& p = data.liMi[k].p;
    const Vector3<S>& z = model.axes[k - 1];
    const Vector3<S> w_parent = R.transpose() * data.omega[k - 1];
    data.omega[k] = w_parent + z * dq(k - 1);
    data.domega[k] =
        R.transpose() * data.domega[k - 1] + z * ddq(k - 1) + w_parent.cross(z * dq(k - 1));
    const Vector3<S>& w0 = data.omega[k - 1];
    data.acc[k] =
        R.transpose() * (data.acc[k - 1] + data.domega[k - 1].cross(p) + w0.cross(w0.cross(p)));

    const Inertia<S>& body = model.inertias[k];
    const Vector3<S> h = body.first_moment();
    const Matrix3<S> I = body.about_origin();
    const Vector3<S>& w = data.omega[k];
    const Vector3<S>& dw = data.domega[k];
    data.force[k] = body.mass * data.acc[k] + dw.cross(h) + w.cross(w.cross(h));
    data.moment[k] = I * dw + w.cross(I * w) + h.cross(data.acc[k]);
  }
  newton_euler_backward_pass(model, data, data.tau);
}

}  // namespace detail

/// Joint torques τ = M(q)q̈ + C(q,q̇)q̇ + G(q) [N·m], M including the armature (reflected rotor
/// inertia) on its diagonal. Result in data.tau (also returned). Runs forward_kinematics.
/// Allocation-free.
template <typename S, int N>
const JointVector<S, N>& rnea(const Model<S, N>& model, Data<S, N>& data,
                              const NoDeduce<JointVector<S, N>>& q,
                              const NoDeduce<JointVector<S, N>>& dq,
                              const NoDeduce<JointVector<S, N>>& ddq) {
  forward_kinematics(model, data, q);
  detail::newton_euler_passes(model, data, dq, ddq, Vector3<S>(-model.gravity));
  data.tau += model.armature.cwiseProduct(ddq);
  return data.tau;
}

/// Joint torques with an external wrench w = [f; m] (world frame) that the environment applies to
/// link `link` at the world point p: τ = RNEA(q, q̇, q̈) − J(p)ᵀ w. This is the torque the motors
/// must produce when the environment pushes with w. Allocation-free.
template <typename S, int N>
const JointVector<S, N>& rnea(const Model<S, N>& model, Data<S, N>& data,
                              const NoDeduce<JointVector<S, N>>& q,
                              const NoDeduce<JointVector<S, N>>& dq,
                              const NoDeduce<JointVector<S, N>>& ddq, int link,
                              const NoDeduce<Vector3<S>>& p, const NoDeduce<Vector6<S>>& wrench) {
  forward_kinematics(model, data, q);
  detail::newton_euler_passes(model, data, dq, ddq, Vector3<S>(-model.gravity));
  // The external wrench, moved to the origin of link `link` and into its frame, acts on every
  // joint from `link` down to the base.
  const Transform<S>& oMl = data.oMi[link];
  Vector3<S> f = oMl.R.transpose() * wrench.template head<3>();
  Vector3<S> m = oMl.R.transpose() *
                 (wrench.template tail<3>() + (p - oMl.p).cross(wrench.template head<3>()));
  for (int k = link; k >= 1; --k) {
    data.tau(k - 1) -= model.axes[k - 1].dot(m);
    const Matrix3<S>& R = data.liMi[k].R;
    m = R * m + data.liMi[k].p.cross(R * f);
    f = R * f;
  }
  data.tau += model.armature.cwiseProduct(ddq);
  return data.tau;
}

/// Gravity torques G(q) = RNEA(q, 0, 0), in data.g. Allocation-free.
template <typename S, int N>
const JointVector<S, N>& compute_gravity(const Model<S, N>& model, Data<S, N>& data,
                                         const NoDeduce<JointVector<S, N>>& q) {
  forward_kinematics(model, data, q);
  const JointVector<S, N> zero = JointVector<S, N>::Zero();
  detail::newton_euler_passes(model, data, zero, zero, Vector3<S>(-model.gravity));
  data.g = data.tau;
  return data.g;
}

/// Velocity-product torques C(q,q̇)q̇ = RNEA(q, q̇, 0) − G(q), in data.tau. Allocation-free.
template <typename S, int N>
const JointVector<S, N>& velocity_torques(const Model<S, N>& model, Data<S, N>& data,
                                          const NoDeduce<JointVector<S, N>>& q,
                                          const NoDeduce<JointVector<S, N>>& dq) {
  forward_kinematics(model, data, q);
  detail::newton_euler_passes(model, data, dq, JointVector<S, N>::Zero().eval(),
                              Vector3<S>::Zero().eval());
  return data.tau;
}

}  // namespace tpf
