// Conversion between a model of run-time joint count (what the loaders and the offline tools hold)
// and one of a joint count fixed at compile time (what a controller's per-cycle path runs on).
#pragma once

#include <string>

#include "tpf/common/error.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// The same model with the joint count as type `To`: Eigen::Dynamic, or a fixed count that must
/// equal the model's (tpf::Error naming both otherwise). Start-up code: copies every member,
/// allocates at Eigen::Dynamic. `joint_count_cast<7>(load_robot<double, Eigen::Dynamic>(file))`.
template <int To, typename S, int From>
Model<S, To> joint_count_cast(const Model<S, From>& from) {
  const int n = from.joint_count();
  require_joint_count<To>(n, ("the model '" + from.name + "'").c_str());
  Model<S, To> to;
  to.resize(n);
  to.name = from.name;
  for (int k = 0; k < n; ++k) {
    to.joint_names[k] = from.joint_names[k];
    to.joint_placements[k] = from.joint_placements[k];
    to.axes[k] = from.axes[k];
    to.joint_types[k] = from.joint_types[k];
  }
  for (int k = 0; k <= n; ++k) {
    to.link_names[k] = from.link_names[k];
    to.inertias[k] = from.inertias[k];
  }
  to.armature = from.armature;
  to.gear_ratio = from.gear_ratio;
  to.torque_constant = from.torque_constant;
  to.current_limit = from.current_limit;
  to.lower = from.lower;
  to.upper = from.upper;
  to.velocity_limit = from.velocity_limit;
  to.effort_limit = from.effort_limit;
  to.gravity = from.gravity;
  to.set_coupling(from.coupling);
  to.update_constants();
  return to;
}

}  // namespace tpf
