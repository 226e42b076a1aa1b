// Turns a loaded robot description into a Model<S, N>: of a fixed N (a controller's, checked
// against the file) or of Eigen::Dynamic (the tools': any joint count).
#pragma once

#include <filesystem>
#include <string>

#include "tpf/common/error.hpp"
#include "tpf/model/model.hpp"
#include "tpf/model/robot_description.hpp"

namespace tpf {

/// Builds a Model<S, N> from a chain; throws tpf::Error if N is fixed and the chain does not have
/// exactly N joints, or if the chain has none.
template <typename S, int N>
Model<S, N> make_model(const ChainDescription& chain) {
  const int n = static_cast<int>(chain.joints.size());
  if (n < 1 || (N != Eigen::Dynamic && n != N)) {
    throw Error::at(chain.source, 0, "",
                    "the chain has " + std::to_string(n) + " joints" +
                        (N != Eigen::Dynamic ? ", this program is built for " + std::to_string(N)
                                             : std::string(", a model needs at least one")));
  }
  Model<S, N> model;
  model.resize(n);
  model.name = chain.robot_name;
  model.link_names[0] = chain.base_link;
  model.inertias[0] = chain.inertias[0].template cast<S>();
  for (int k = 0; k < n; ++k) {
    const ChainJoint& j = chain.joints[k];
    model.joint_names[k] = j.name;
    model.link_names[k + 1] = j.child_link;
    model.joint_placements[k] = j.placement.template cast<S>();
    model.axes[k] = j.axis.template cast<S>();
    model.joint_types[k] = j.type;
    model.inertias[k + 1] = chain.inertias[k + 1].template cast<S>();
    model.lower(k) = S(j.lower);
    model.upper(k) = S(j.upper);
    model.velocity_limit(k) = S(j.velocity_limit);
    model.effort_limit(k) = S(j.effort_limit);
  }
  model.update_constants();
  return model;
}

/// Builds a Model<S, N> from a full robot description (chain + drives + gravity).
template <typename S, int N>
Model<S, N> make_model(const RobotDescription& robot) {
  Model<S, N> model = make_model<S, N>(robot.chain);
  for (int k = 0; k < model.joint_count(); ++k) {
    const DriveDescription& d = robot.drives[k];
    model.armature(k) = S(d.armature());
    model.gear_ratio(k) = S(d.gear_ratio);
    model.torque_constant(k) = S(d.torque_constant);
    model.current_limit(k) = S(d.current_limit);
  }
  model.gravity = robot.gravity.template cast<S>();
  if (robot.coupling.size() > 0) model.set_coupling(robot.coupling.template cast<S>());
  return model;
}

/// Loads a robot file (data/arm4.robot.json) into a Model<S, N>: `tpf::load_robot<double, 4>(path)`
/// in a controller, `tpf::load_robot<double, Eigen::Dynamic>(path)` for any joint count.
template <typename S, int N>
Model<S, N> load_robot(const std::filesystem::path& robot_file) {
  return make_model<S, N>(load_robot_description(robot_file));
}

}  // namespace tpf
