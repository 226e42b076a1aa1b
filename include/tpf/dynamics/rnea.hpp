// Inverse dynamics by the recursive Newton–Euler algorithm, with armature.
#pragma once

#include "tpf/common/small_products.hpp"
#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf {
namespace detail {

/// The backward Newton–Euler pass on the link forces f_k and moments n_k (link frames, about the
/// link origin) in data.force/data.moment: f_k += R_{k+1} f_{k+1},
/// n_k += R_{k+1} n_{k+1} + p_{k+1} × R_{k+1} f_{k+1}, then τ_k = z_k·n_k (revolute) or z_k·f_k
/// (prismatic; the type tested only when kPrismatic).
template <bool kPrismatic, typename S, int N>
[[gnu::flatten]] void newton_euler_backward_pass(const Model<S, N>& model, Data<S, N>& data,
                                                 JointVector<S, N>& tau) noexcept {
  const int last = model.joint_count();
  Vector3<S> f = data.force[last], n = data.moment[last];
  tau(last - 1) = model.axes[last - 1].dot(n);
  for (int k = last - 1; k >= 1; --k) {
    const Matrix3<S>& R = data.liMi[k + 1].R;
    const Vector3<S> f_child = R * f;
    n = data.moment[k] + (R * n + data.liMi[k + 1].p.cross(f_child));
    f = data.force[k] + f_child;
    data.force[k] = f;
    data.moment[k] = n;
    tau(k - 1) = model.axes[k - 1].dot(n);
  }
  if constexpr (kPrismatic) {
    for (int k = 1; k <= last; ++k)
      if (model.joint_types[k - 1] == JointType::prismatic)
        tau(k - 1) = model.axes[k - 1].dot(data.force[k]);
  }
}

/// The backward pass of every form of the inverse dynamics (standard inertias here, linear link
/// parameters in estimation), for the model's joint types.
template <typename S, int N>
void newton_euler_backward_pass(const Model<S, N>& model, Data<S, N>& data,
                                JointVector<S, N>& tau) noexcept {
  if (model.constants.has_prismatic)
    out_of_line([&] { newton_euler_backward_pass<true>(model, data, tau); });
  else
    newton_euler_backward_pass<false>(model, data, tau);
}

/// The two Newton–Euler passes on the joint transforms already in data.liMi, with base linear
/// acceleration a0 (−g for the full dynamics, 0 for velocity terms only). Writes data.tau without
/// the armature term. Link quantities are in link frames; each link's first moment and inertia
/// about its origin are the model's constants. A prismatic joint (tested only when kPrismatic)
/// keeps ω and ω̇ and adds z q̈ + 2ω × z q̇ to the origin's acceleration.
template <bool kPrismatic, typename S, int N>
[[gnu::flatten]] void newton_euler_passes(const Model<S, N>& model, Data<S, N>& data,
                                          const NoDeduce<JointVector<S, N>>& dq,
                                          const NoDeduce<JointVector<S, N>>& ddq,
                                          const NoDeduce<Vector3<S>>& a0) noexcept {
  const ModelConstants<S, N>& c = model.constants;
  // The recursion runs on locals (registers), not through data's arrays: storing ω, ω̇, a and
  // reading them back a link later put a store-to-load round trip on the critical path.
  Vector3<S> w = Vector3<S>::Zero(), dw = Vector3<S>::Zero(), a = a0;
  data.omega[0] = w;
  data.domega[0] = dw;
  data.acc[0] = a;
  const int n = model.joint_count();
  for (int k = 1; k <= n; ++k) {
    const Matrix3<S>& R = data.liMi[k].R;
    const Vector3<S>& p = data.liMi[k].p;
    const Vector3<S>& z = model.axes[k - 1];
    const Vector3<S> joint_rate = z * dq(k - 1);
    const Vector3<S> origin_acc = a + dw.cross(p) + w.cross(w.cross(p));
    const Vector3<S> w_parent = R.transpose() * w;
    if constexpr (kPrismatic) {
      if (model.joint_types[k - 1] == JointType::prismatic) {
        dw = R.transpose() * dw;
        w = w_parent;
        a = R.transpose() * origin_acc + z * ddq(k - 1) + S(2) * w.cross(joint_rate);
      } else {
        dw = R.transpose() * dw + z * ddq(k - 1) + w_parent.cross(joint_rate);
        w = w_parent + joint_rate;
        a = R.transpose() * origin_acc;
      }
    } else {
      dw = R.transpose() * dw + z * ddq(k - 1) + w_parent.cross(joint_rate);
      w = w_parent + joint_rate;
      a = R.transpose() * origin_acc;
    }
    data.omega[k] = w;
    data.domega[k] = dw;
    data.acc[k] = a;

    const Vector3<S>& h = c.first_moment[k];
    const Matrix3<S>& I = c.inertia_about_origin[k];
    data.force[k] = model.inertias[k].mass * a + dw.cross(h) + w.cross(w.cross(h));
    data.moment[k] = I * dw + w.cross(I * w) + h.cross(a);
  }
  newton_euler_backward_pass<kPrismatic>(model, data, data.tau);
}

/// newton_euler_passes for the model's joint types: the revolute-only recursion unless the model
/// has a prismatic joint.
template <typename S, int N>
void newton_euler_passes(const Model<S, N>& model, Data<S, N>& data,
                         const NoDeduce<JointVector<S, N>>& dq,
                         const NoDeduce<JointVector<S, N>>& ddq,
                         const NoDeduce<Vector3<S>>& a0) noexcept {
  if (model.constants.has_prismatic)
    out_of_line([&] { newton_euler_passes<true>(model, data, dq, ddq, a0); });
  else
    newton_euler_passes<false>(model, data, dq, ddq, a0);
}

/// gravity_at_pose for the joint types: a prismatic joint k carries G_k = m_{k..N} z_k · a_k.
template <bool kPrismatic, typename S, int N>
[[gnu::flatten]] void gravity_passes(const Model<S, N>& model, Data<S, N>& data) noexcept {
  const ModelConstants<S, N>& c = model.constants;
  const auto joint_effort = [&](int k, const Vector3<S>& H, const Vector3<S>& a) {
    if (kPrismatic && model.joint_types[k - 1] == JointType::prismatic)
      return c.subtree_mass[k] * detail::dot(model.axes[k - 1], a);
    return detail::dot(model.axes[k - 1], detail::cross(H, a));
  };
  // Both recursions run on locals, each value stored once (no store-to-load round trip).
  const int n = model.joint_count();
  Vector3<S> a = -model.gravity;
  data.acc[0] = a;
  for (int k = 1; k <= n; ++k) {
    a = detail::rotate_back(data.liMi[k].R, a);
    data.acc[k] = a;
  }
  Vector3<S> H = c.first_moment[n];
  data.composite_first_moment[n] = H;
  data.g(n - 1) = joint_effort(n, H, a);
  for (int k = n - 1; k >= 1; --k) {
    const Transform<S>& child = data.liMi[k + 1];
    H = detail::rotate(child.R, H) + (c.first_moment[k] + c.subtree_mass[k + 1] * child.p);
    data.composite_first_moment[k] = H;
    data.g(k - 1) = joint_effort(k, H, data.acc[k]);
  }
}

/// tau += Cᵀ·diag(armature)·C·q̈ (armature·q̈ per joint without a coupling).
template <typename S, int N>
void add_armature(const Model<S, N>& model, const JointVector<S, N>& ddq, JointVector<S, N>& tau) {
  if (!model.coupled) {
    tau += model.armature.cwiseProduct(ddq);
    return;
  }
  for (int m = 0; m < model.joint_count(); ++m)
    model.add_motor_torque(m, model.armature(m) * model.motor_rate(m, ddq), tau);
}

}  // namespace detail

/// Joint efforts τ = M(q)q̈ + C(q,q̇)q̇ + G(q) [N·m, or N at a prismatic joint], M including the
/// armature (reflected rotor inertia, or mass) on its diagonal. The result lives in data.tau (the
/// returned reference): the next dynamics call on `data` (compute_gravity, another rnea, …)
/// overwrites it, so copy what you keep. Runs joint_transforms (data.liMi at q; data.oMi is left as
/// it was: forward_kinematics gives the link poses). Allocation-free.
template <typename S, int N>
const JointVector<S, N>& rnea(const Model<S, N>& model, Data<S, N>& data,
                              const NoDeduce<JointVector<S, N>>& q,
                              const NoDeduce<JointVector<S, N>>& dq,
                              const NoDeduce<JointVector<S, N>>& ddq) {
  joint_transforms(model, data, q);
  detail::newton_euler_passes(model, data, dq, ddq, Vector3<S>(-model.gravity));
  detail::add_armature(model, ddq, data.tau);
  return data.tau;
}

/// Joint torques with an external wrench w = [f; m] (world frame) that the environment applies to
/// link `link` at the world point p: τ = RNEA(q, q̇, q̈) − J(p)ᵀ w. This is the torque the motors
/// must produce when the environment pushes with w. Runs forward_kinematics. Allocation-free.
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
    data.tau(k - 1) -= model.axes[k - 1].dot(model.is_prismatic(k - 1) ? f : m);
    const Matrix3<S>& R = data.liMi[k].R;
    m = R * m + data.liMi[k].p.cross(R * f);
    f = R * f;
  }
  detail::add_armature(model, ddq, data.tau);
  return data.tau;
}

/// Gravity torques G(q) = RNEA(q, 0, 0) on the joint transforms already in data.liMi
/// (joint_transforms or forward_kinematics at q first), in data.g, by a gravity-only pass: with
/// the base acceleration a_0 = −g carried into each link frame, a_k = R_kᵀ a_{k−1}, and the first
/// moment of links k..N about link k's origin, H_k = h_k + R_{k+1} H_{k+1} + m_{k+1..N} p_{k+1},
/// G_k = z_k · (H_k × a_k) for a revolute joint, m_{k..N} z_k · a_k for a prismatic one.
/// Overwrites data.acc and data.composite_first_moment. Allocation-free.
template <typename S, int N>
const JointVector<S, N>& gravity_at_pose(const Model<S, N>& model, Data<S, N>& data) noexcept {
  if (model.constants.has_prismatic)
    detail::out_of_line([&] { detail::gravity_passes<true>(model, data); });
  else
    detail::gravity_passes<false>(model, data);
  return data.g;
}

/// Gravity torques G(q) = RNEA(q, 0, 0), in data.g: joint_transforms (data.liMi at q; data.oMi is
/// left as it was), then gravity_at_pose. Allocation-free.
template <typename S, int N>
const JointVector<S, N>& compute_gravity(const Model<S, N>& model, Data<S, N>& data,
                                         const NoDeduce<JointVector<S, N>>& q) noexcept {
  joint_transforms(model, data, q);
  return gravity_at_pose(model, data);
}

/// Velocity-product torques C(q,q̇)q̇ = RNEA(q, q̇, 0) − G(q), in data.tau. Runs joint_transforms.
/// Allocation-free.
template <typename S, int N>
const JointVector<S, N>& velocity_torques(const Model<S, N>& model, Data<S, N>& data,
                                          const NoDeduce<JointVector<S, N>>& q,
                                          const NoDeduce<JointVector<S, N>>& dq) {
  joint_transforms(model, data, q);
  detail::newton_euler_passes(model, data, dq, JointVector<S, N>::Zero(model.joint_count()).eval(),
                              Vector3<S>::Zero().eval());
  return data.tau;
}

}  // namespace tpf
