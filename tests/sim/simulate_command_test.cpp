// `tpf simulate` end to end on the 9-joint test robot (tests/sim/arm9): the built binary writes a
// log whose header names q1 … q9 and every other per-joint and per-pad column, whose metadata
// carries the robot file's torque constants, and whose rows are the library's simulate_to_log.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "offline/log/read_log.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/temp_dir.hpp"
#include "tpf/model/robot_description.hpp"

namespace {

using namespace tpf::offline;

const std::string kArm9Dir = TPF_SIM_TEST_DIR "/arm9";

#ifdef TPF_CLI
std::string text_of(const std::filesystem::path& path) {
  std::ostringstream s;
  s << std::ifstream(path, std::ios::binary).rdbuf();
  return s.str();
}

// Runs `tpf <args>` in `dir`; returns the exit status, stderr in `err`.
int run_tpf(const std::filesystem::path& dir, const std::string& args, std::string& err) {
  const std::string command =
      "cd '" + dir.string() + "' && '" TPF_CLI "' " + args + " >.stdout 2>.stderr";
  const int status = std::system(command.c_str());
  err = text_of(dir / ".stderr");
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

// The header line of a log file: the first line that is not a '#' comment.
std::string header_line(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') return line;
  return "";
}
#endif

TEST(SimulateCommand, WritesANineJointLogWithItsColumnsAndTheLibrarysRows) {
#ifndef TPF_CLI
  GTEST_SKIP() << "the tpf command is not built (TPF_BUILD_OFFLINE=OFF)";
#else
  const tpf::test::TempDir dir("simulate_command_arm9");
  std::string err;
  ASSERT_EQ(run_tpf(dir.path(),
                    "simulate --scenario " + kArm9Dir +
                        "/arm9-excitation.json --seed 17 --duration 3 --out arm9.csv",
                    err),
            0)
      << err;
  EXPECT_NE(err.find("arm9.robot.json, 9 joints"), std::string::npos) << err;

  std::ostringstream expected_header;
  expected_header << "t";
  for (const char* prefix : {"q", "dq", "i"})
    for (int j = 1; j <= 9; ++j)
      expected_header << ',' << prefix << j;
  for (int k = 1; k <= 6; ++k)
    expected_header << ",p" << k;
  for (const char* prefix : {"temp", "gt_fric", "gt_tau_ext", "gt_ddq"})
    for (int j = 1; j <= 9; ++j)
      expected_header << ',' << prefix << j;
  expected_header << ",gt_contact,gt_fx,gt_fy,gt_fz";
  EXPECT_EQ(header_line(dir / "arm9.csv"), expected_header.str());

  const Log log = read_log(dir / "arm9.csv");
  EXPECT_EQ(log.meta.get("robot").value_or(""), "arm9");
  const tpf::RobotDescription robot = tpf::load_robot_description(kArm9Dir + "/arm9.robot.json");
  std::string torque_constants;
  for (std::size_t j = 0; j < robot.drives.size(); ++j) {
    std::ostringstream s;
    s.precision(17);
    s << (j ? "," : "") << robot.drives[j].torque_constant;
    torque_constants += s.str();
  }
  EXPECT_EQ(log.meta.get("torque_constant_nm_per_a").value_or(""), torque_constants);

  const Log library = simulate_to_log(load_scenario(kArm9Dir + "/arm9-excitation.json"), 17, 3.0);
  ASSERT_EQ(log.rows(), library.rows());
  ASSERT_GT(log.rows(), 1150);
  ASSERT_EQ(log.columns, library.columns);
  for (Eigen::Index c = 0; c < log.values.cols(); ++c)
    for (Eigen::Index k = 0; k < log.rows(); ++k)
      ASSERT_NEAR(log.values(k, c), library.values(k, c),
                  1e-12 * std::max(1.0, std::abs(library.values(k, c))))
          << log.columns[static_cast<std::size_t>(c)] << ", row " << k;
#endif
}

TEST(SimulateCommand, RobotOptionRunsAnyArmOnAScenarioWithoutPerJointVectors) {
#ifndef TPF_CLI
  GTEST_SKIP() << "the tpf command is not built (TPF_BUILD_OFFLINE=OFF)";
#else
  const tpf::test::TempDir dir("simulate_command_robot");
  // A scenario for the 4-joint arm (the default robot) that names no per-joint vector.
  std::ofstream(dir / "contacts.json") << R"({"kind": "static-contacts", "duration_s": 2})";
  std::string err;
  ASSERT_EQ(run_tpf(dir.path(),
                    "simulate --quiet --scenario contacts.json --robot " + kArm9Dir +
                        "/arm9.robot.json --seed 3 --out log.csv",
                    err),
            0)
      << err;
  const Log log = read_log(dir / "log.csv");
  EXPECT_EQ(log.columns, simulation_columns(9, 6));
  EXPECT_GT(log.rows(), 750);
  EXPECT_EQ(log.meta.get("robot").value_or(""), "arm9");

  // The 4-joint scenarios' per-joint vectors do not fit: refused, naming the key and the count.
  EXPECT_EQ(run_tpf(dir.path(),
                    "simulate --quiet --scenario " TPF_TEST_DATA_DIR
                    "/scenarios/excitation.json --robot " +
                        kArm9Dir + "/arm9.robot.json --out refused.csv",
                    err),
            1);
  EXPECT_NE(err.find("initial_q"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(dir / "refused.csv"));
#endif
}

}  // namespace
