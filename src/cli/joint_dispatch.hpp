// Runs a command's work with the joint count N of an arm, fixed at compile time (the core is
// templated on N): one place decides which N the tools are built for (1 … kMaxJoints).
#pragma once

#include <string>
#include <utility>

#include "robot_joint_count.hpp"
#include "tpf/common/error.hpp"
#include "tpf/common/joint_counts.hpp"

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

/// with_joint_count on a log's joint count, once the robot file is checked to have as many
/// joints (require_log_joint_count).
template <typename Work>
void with_log_joint_count(int log_joints, const std::string& log_source,
                          const std::string& robot_file, Work&& work) {
  require_log_joint_count(log_joints, log_source, robot_file);
  with_joint_count(log_joints, log_source, std::forward<Work>(work));
}

}  // namespace tpf::cli
