// The check that a log was made by the arm a robot file describes, for every tool that reads both.
#pragma once

#include <string>

#include "tpf/common/error.hpp"

namespace tpf::offline {

/// Checks that the robot file `robot_file` (of `robot_joints` joints) has as many joints as a log
/// of `log_joints` joints read from `log_source`: otherwise a tpf::Error names both ("ex.csv: the
/// log has 2 joints (q1 … q2), the robot file arm.robot.json has 1: " + `remedy`).
inline void require_log_joint_count(int log_joints, const std::string& log_source, int robot_joints,
                                    const std::string& robot_file, const std::string& remedy) {
  if (robot_joints != log_joints)
    throw Error::at(log_source, 0, "",
                    "the log has " + std::to_string(log_joints) + " joints (q1 … q" +
                        std::to_string(log_joints) + "), the robot file " + robot_file + " has " +
                        std::to_string(robot_joints) + ": " + remedy);
}

}  // namespace tpf::offline
