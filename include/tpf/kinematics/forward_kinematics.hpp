// Forward kinematics: link poses in the world frame.
#pragma once

#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// Link poses for joint positions q [rad]: data.liMi[k] = placement_k · Rot(axis_k, q_k),
/// data.oMi[k] = data.oMi[k−1] · data.liMi[k] (oMi[0] = identity, the base is the world frame), and
/// data.axis_world[k] = oMi[k].R · axis_k. Allocation-free.
template <typename S, int N>
void forward_kinematics(const Model<S, N>& model, Data<S, N>& data,
                        const NoDeduce<JointVector<S, N>>& q) {
  data.oMi[0] = Transform<S>{};
  for (int k = 1; k <= N; ++k) {
    const Transform<S>& placement = model.joint_placements[k - 1];
    const Matrix3<S> rotation = Eigen::AngleAxis<S>(q(k - 1), model.axes[k - 1]).toRotationMatrix();
    data.liMi[k].R.noalias() = placement.R * rotation;
    data.liMi[k].p = placement.p;
    data.oMi[k] = data.oMi[k - 1] * data.liMi[k];
    data.axis_world[k].noalias() = data.oMi[k].R * model.axes[k - 1];
  }
}

/// World position of a point given in link k's frame. Needs forward_kinematics first.
template <typename S, int N>
Vector3<S> world_point(const Data<S, N>& data, int link,
                       const NoDeduce<Vector3<S>>& point_in_link) {
  return data.oMi[link].apply(point_in_link);
}

}  // namespace tpf
