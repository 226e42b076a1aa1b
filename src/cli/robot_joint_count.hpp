// The joint count of a robot file, and the check that a log was made by that arm.
#pragma once

#include <string>

#include "offline/log/log_joint_count.hpp"
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
  offline::require_log_joint_count(log_joints, log_source, robot_joint_count(robot_file),
                                   robot_file,
                                   "give the robot file of the arm that made the log (--robot)");
}

}  // namespace tpf::cli
