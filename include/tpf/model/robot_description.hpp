// Start-up loading of a robot: the URDF chain and the drive data that URDF cannot hold.
// These functions allocate and throw tpf::Error; call them once, before the control loop.
#pragma once

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "tpf/common/types.hpp"
#include "tpf/model/inertia.hpp"

namespace tpf {

/// One revolute joint of a serial chain, with fixed joints already folded in.
struct ChainJoint {
  std::string name;
  std::string child_link;
  Transform<double> placement;  ///< joint frame in the previous moving link's frame.
  Vector3<double> axis;         ///< unit, joint frame.
  double lower = 0, upper = 0;
  /// [rad/s], [N·m]; +∞ for a joint without <limit> (a continuous joint needs none).
  double velocity_limit = std::numeric_limits<double>::infinity();
  double effort_limit = std::numeric_limits<double>::infinity();
};

/// A serial chain of revolute joints read from a URDF. Fixed joints are merged: a fixed child's
/// inertia is added to the moving link it hangs from, and fixed offsets go into the next placement.
struct ChainDescription {
  std::string source;  ///< the file it came from, for messages.
  std::string robot_name;
  std::string base_link;
  std::vector<ChainJoint> joints;
  std::vector<Inertia<double>> inertias;  ///< [0] base, then one per joint's child link.
};

/// Drive data per joint (what URDF cannot hold).
struct DriveDescription {
  std::string joint;
  std::string motor;
  double gear_ratio = 1;
  double rotor_inertia = 0;    ///< [kg·m²] motor side.
  double torque_constant = 1;  ///< [N·m/A] output side.
  double current_limit = 0;    ///< [mA].
  double armature() const { return rotor_inertia * gear_ratio * gear_ratio; }
};

/// A robot file (data/<robot>.robot.json): URDF chain + drives + gravity + the pad layout path.
struct RobotDescription {
  std::string source;
  ChainDescription chain;
  std::vector<DriveDescription> drives;  ///< in chain order.
  Vector3<double> gravity{0, 0, -9.81};
  std::filesystem::path pads_file;      ///< empty if the robot has no skin.
  std::filesystem::path friction_file;  ///< the twin's true friction; empty if none is named.
};

/// Reads a URDF and extracts the serial chain of revolute (or continuous) joints from its root.
/// Refuses, naming the file and the joint or link: malformed XML, a branching tree, prismatic,
/// floating or planar joints, a zero axis, a negative mass or an inertia that is not positive
/// semi-definite, a body moved by a joint in which no link has an <inertial> (an <inertial> with
/// mass 0 is allowed; a link without one fixed to a link with one is massless). An inertia that
/// breaks the triangle inequality is loaded with a warning (makers' files do: the Gen3's).
ChainDescription load_urdf_chain(const std::filesystem::path& urdf_file);

/// Reads a robot file (JSON, format "tpf-robot" version 1) and the URDF it names (relative paths
/// are taken from the robot file's folder). Every drive must name a joint of the chain, in order.
RobotDescription load_robot_description(const std::filesystem::path& robot_file);

}  // namespace tpf
