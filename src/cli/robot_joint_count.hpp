// The joint count of a robot file, and the check that a log was made by that arm.
#pragma once

#include <string>

#include "tpf/common/error.hpp"
#include "tpf/model/robot_description.hpp"

namespace tpf::cli {

/// The joint count of the robot file's chain.
inline int robot_joint_count(const std::string& robot_file) {
  return static_cast<int>(load_robot_description(robot_file).chain.joints.size());
}

/// Checks that the robot file has as many joints as a log of `log_joints` joints: otherwise a
/// tpf::Error names both ("ex.csv has 2 joints, arm.robot.json has 1").
inline void require_log_joint_count(int log_joints, const std::string& log_source,
                                    const std::string& robot_file) {
  const int robot_joints = robot_joint_count(robot_file);
  if (robot_joints != log_joints)
    throw Error::at(log_source, 0, "",
                    "the log has " + std::to_string(log_joints) + " joints (q1 … q" +
                        std::to_string(log_joints) + "), the robot file " + robot_file + " has " +
                        std::to_string(robot_joints) +
                        ": give the robot file of the arm that made the log (--robot)");
}

}  // namespace tpf::cli
