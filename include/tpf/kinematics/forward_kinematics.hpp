// Forward kinematics: joint transforms and link poses in the world frame.
#pragma once

#include <cassert>

#include "tpf/kinematics/sin_cos.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// The last_link of link_poses and forward_kinematics that means every link of the model.
inline constexpr int kAllLinks = -1;

namespace detail {

/// The link count a kinematics call runs to: last_link, or the model's joint count for kAllLinks.
inline int resolve_last_link(int last_link, int joint_count) noexcept {
  assert(last_link >= kAllLinks && last_link <= joint_count);
  return last_link == kAllLinks ? joint_count : last_link;
}

/// data.liMi[k] = placement_k · Rot(axis_k, q_k), the rotation by Rodrigues' formula on the
/// model's constants: placement.R + sin q·placement.R[z]× + (1 − cos q)·placement.R[z]×²; for a
/// prismatic joint (tested only when kPrismatic: the model has one), placement_k · Trans(axis_k
/// q_k): R = placement.R, p = placement.p + q·placement.R·axis.
template <bool kPrismatic, typename S, int N>
inline void joint_transform(const Model<S, N>& model, Data<S, N>& data, int k, S q) noexcept {
  const ModelConstants<S, N>& c = model.constants;
  if constexpr (kPrismatic) {
    if (model.joint_types[k - 1] == JointType::prismatic) {
      data.liMi[k].R = model.joint_placements[k - 1].R;
      data.liMi[k].p = model.joint_placements[k - 1].p + q * c.translation_axis[k - 1];
      return;
    }
  }
  S sine, cosine;
  sin_cos(q, sine, cosine);
  const S versine = S(1) - cosine;
  data.liMi[k].R = model.joint_placements[k - 1].R + sine * c.rotation_sine[k - 1] +
                   versine * c.rotation_versine[k - 1];
  data.liMi[k].p = model.joint_placements[k - 1].p;
}

/// data.axis_world[k] = oMi[k].R · axis_k: a column of the rotation when the axis is a coordinate
/// axis (the same numbers as the product, whose other terms are exact zeros).
template <typename S, int N>
inline void world_axis(const Model<S, N>& model, Data<S, N>& data, int k) noexcept {
  const int a = model.constants.axis_coordinate[k - 1];
  if (a > 0)
    data.axis_world[k] = data.oMi[k].R.col(a - 1);
  else if (a < 0)
    data.axis_world[k] = -data.oMi[k].R.col(-a - 1);
  else
    data.axis_world[k].noalias() = data.oMi[k].R * model.axes[k - 1];
}

}  // namespace detail

/// The joint transforms alone, data.liMi[k] = placement_k · Rot(axis_k, q_k) (link k in link k−1;
/// Trans(axis_k q_k) for a prismatic joint) for joint positions q [rad or m]: all the dynamics
/// needs. Leaves data.oMi and data.axis_world as they were. Allocation-free.
template <typename S, int N>
void joint_transforms(const Model<S, N>& model, Data<S, N>& data,
                      const NoDeduce<JointVector<S, N>>& q) noexcept {
  assert(model.constants_current() && "Model::update_constants() after editing the model");
  const int n = model.joint_count();
  if (model.constants.has_prismatic) {
    detail::out_of_line([&] {
      for (int k = 1; k <= n; ++k)
        detail::joint_transform<true>(model, data, k, q(k - 1));
    });
    return;
  }
  for (int k = 1; k <= n; ++k)
    detail::joint_transform<false>(model, data, k, q(k - 1));
}

/// Link poses from the joint transforms already in data.liMi (joint_transforms at q first), from
/// the base to link `last_link` (kAllLinks: every link): data.oMi[k] = data.oMi[k−1] · data.liMi[k]
/// (oMi[0] = identity, the base is the world frame) and data.axis_world[k] = oMi[k].R · axis_k.
/// Links beyond `last_link` keep what they held. A per-cycle caller whose dynamics ran on
/// joint_transforms pays for the poses only where it needs them (a contact Jacobian at link k:
/// links 1..k). Allocation-free.
template <typename S, int N>
void link_poses(const Model<S, N>& model, Data<S, N>& data, int last_link = kAllLinks) noexcept {
  const int last = detail::resolve_last_link(last_link, model.joint_count());
  data.oMi[0] = Transform<S>{};
  for (int k = 1; k <= last; ++k) {
    const Transform<S>& parent = data.oMi[k - 1];
    data.oMi[k].R.noalias() = parent.R * data.liMi[k].R;
    data.oMi[k].p.noalias() = parent.R * data.liMi[k].p;
    data.oMi[k].p += parent.p;
    detail::world_axis(model, data, k);
  }
}

/// Link poses for joint positions q [rad or m], from the base to link `last_link` (every link by
/// default; a Jacobian at a point of link k needs links 1..k): data.liMi[k] (as joint_transforms)
/// and, as link_poses, data.oMi[k] and data.axis_world[k]. Links beyond `last_link` keep what they
/// held. Allocation-free.
template <typename S, int N>
void forward_kinematics(const Model<S, N>& model, Data<S, N>& data,
                        const NoDeduce<JointVector<S, N>>& q, int last_link = kAllLinks) noexcept {
  assert(model.constants_current() && "Model::update_constants() after editing the model");
  const int last = detail::resolve_last_link(last_link, model.joint_count());
  if (model.constants.has_prismatic) {
    detail::out_of_line([&] {
      for (int k = 1; k <= last; ++k)
        detail::joint_transform<true>(model, data, k, q(k - 1));
    });
  } else {
    for (int k = 1; k <= last; ++k)
      detail::joint_transform<false>(model, data, k, q(k - 1));
  }
  link_poses(model, data, last);
}

/// World position of a point given in link k's frame. Needs forward_kinematics first.
template <typename S, int N>
Vector3<S> world_point(const Data<S, N>& data, int link,
                       const NoDeduce<Vector3<S>>& point_in_link) {
  return data.oMi[link].apply(point_in_link);
}

}  // namespace tpf
