// The measured Kinova Gen3 files the tests read (data/real/kinova-gen3/): the robot file and the
// measured loop's split, three fitting files and two scored ones.
#pragma once

#include <string>
#include <vector>

#include "tpf/model/load_robot.hpp"

namespace tpf::test {

inline std::string kinova_dir() {
  return std::string(TPF_TEST_DATA_DIR) + "/real/kinova-gen3/";
}

inline Model<double, 7> kinova_model() {
  return load_robot<double, 7>(kinova_dir() + "gen3.robot.json");
}

inline std::vector<std::string> kinova_fitting_files() {
  const std::string logs = kinova_dir() + "logs/";
  return {logs + "RunTrajectory1.csv.gz", logs + "Trajectory1.csv.gz",
          logs + "RecordTrajectory_quadratic.csv.gz"};
}

inline std::vector<std::string> kinova_testing_files() {
  const std::string logs = kinova_dir() + "logs/";
  return {logs + "opti_traj_testing1.csv.gz", logs + "opti_traj_testing2.csv.gz"};
}

}  // namespace tpf::test
