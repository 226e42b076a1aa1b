// The geometric Jacobian of a point fixed to a link.
#pragma once

#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// Jacobian J (6×N, rows [linear; angular], world frame) of the point p (world coordinates) fixed
/// to link `link` (1..N): for every joint i ≤ link, J_v,i = z_i × (p − p_i) and J_ω,i = z_i for a
/// revolute joint, J_v,i = z_i and J_ω,i = 0 for a prismatic one, with z_i and p_i the world axis
/// and origin of joint i; columns of joints beyond `link` are zero.
/// [v; ω] = J q̇, and a force f with moment m at p maps to joint torques τ = Jᵀ [f; m].
/// Needs forward_kinematics first. Allocation-free.
template <typename S, int N>
void point_jacobian(const Model<S, N>& model, const Data<S, N>& data, int link,
                    const NoDeduce<Vector3<S>>& p, Jacobian<S, N>& J) {
  J.setZero(6, model.joint_count());
  if (model.constants.has_prismatic) {
    detail::out_of_line([&] {
      for (int i = 1; i <= link; ++i) {
        const Vector3<S>& z = data.axis_world[i];
        if (model.joint_types[i - 1] == JointType::prismatic) {
          J.template block<3, 1>(0, i - 1) = z;
        } else {
          J.template block<3, 1>(0, i - 1) = z.cross(p - data.oMi[i].p);
          J.template block<3, 1>(3, i - 1) = z;
        }
      }
    });
    return;
  }
  for (int i = 1; i <= link; ++i) {
    const Vector3<S>& z = data.axis_world[i];
    J.template block<3, 1>(0, i - 1) = z.cross(p - data.oMi[i].p);
    J.template block<3, 1>(3, i - 1) = z;
  }
}

/// Convenience form of point_jacobian that returns J.
template <typename S, int N>
Jacobian<S, N> point_jacobian(const Model<S, N>& model, const Data<S, N>& data, int link,
                              const NoDeduce<Vector3<S>>& p) {
  Jacobian<S, N> J;
  point_jacobian(model, data, link, p, J);
  return J;
}

/// The same Jacobian expressed in a local frame whose axes are the columns of R (world
/// coordinates), e.g. a contact frame: J_local = diag(Rᵀ, Rᵀ) · J_world.
template <typename S, int N>
Jacobian<S, N> rotate_jacobian(const Jacobian<S, N>& J_world, const Matrix3<S>& R) {
  Jacobian<S, N> J(6, J_world.cols());
  J.template topRows<3>().noalias() = R.transpose() * J_world.template topRows<3>();
  J.template bottomRows<3>().noalias() = R.transpose() * J_world.template bottomRows<3>();
  return J;
}

}  // namespace tpf
