// Runs a command's work with the joint count N of an arm, fixed at compile time (the core is
// templated on N): one place decides which N the tools are built for (1 … kMaxJoints).
#pragma once

#include <string>
#include <utility>

#include "tpf/common/error.hpp"
#include "tpf/common/joint_counts.hpp"
#include "tpf/model/robot_description.hpp"

namespace tpf::cli {

/// Calls `work.template operator()<N>()` with N = `joints`, e.g.
///   with_joint_count(log.joint_count(), log.source, [&]<int N>() { run<N>(log, args); });
/// Any other count is refused with a tpf::Error naming `source`.
template <typename Work>
void with_joint_count(int joints, const std::string& source, Work&& work) {
  if (joints < 1 || joints > kMaxJoints)
    throw Error::at(source, 0, "",
                    "arms of 1 to " + std::to_string(kMaxJoints) +
                        " joints are supported, this one has " + std::to_string(joints));
  const auto run_if = [&]<int J>() {
    if (joints != J) return false;
    work.template operator()<J>();
    return true;
  };
  const auto first_match = [&]<int... K>(std::integer_sequence<int, K...>) {
    return (run_if.template operator()<K + 1>() || ...);
  };
  first_match(std::make_integer_sequence<int, kMaxJoints>{});
}

/// The joint count of the robot file's chain (what the commands dispatch on).
inline int robot_joint_count(const std::string& robot_file) {
  return static_cast<int>(load_robot_description(robot_file).chain.joints.size());
}

/// Checks that the robot file has the log's joint count: otherwise a tpf::Error names both
/// ("ex.csv has 2 joints, arm.robot.json has 1"). Any count that agrees is accepted.
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

/// with_joint_count on a log's joint count, once require_log_joint_count has checked the robot
/// file against it.
template <typename Work>
void with_log_joint_count(int log_joints, const std::string& log_source,
                          const std::string& robot_file, Work&& work) {
  require_log_joint_count(log_joints, log_source, robot_file);
  with_joint_count(log_joints, log_source, std::forward<Work>(work));
}

}  // namespace tpf::cli
