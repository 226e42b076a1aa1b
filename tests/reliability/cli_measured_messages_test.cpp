// The `tpf` binary on the shipped Kinova Gen3 logs (MEASURED): the fitting and scoring commands
// name the flat torque sensors of each file (docs/log-format.md), and on a log too short to hold
// anything out identify and diagnose say so instead of printing NaN or "no gain" without a word.
#include <gtest/gtest.h>

#include <string>

#include "cli_runner.hpp"

namespace tpf::test {
namespace {

const std::string kKinova = std::string(TPF_TEST_DATA_DIR) + "/real/kinova-gen3/";

void expect_contains(const CliResult& r, const std::string& text) {
  EXPECT_NE(r.out.find(text), std::string::npos) << "missing '" << text << "' in:\n"
                                                 << r.out << r.err;
}

TEST(CliMeasuredMessages, FlatSensorsAreNamedAndNothingHeldOutIsSaid) {
  CliSandbox box("measured_messages");
  const std::string robot = " --robot " + kKinova + "gen3.robot.json";
  const std::string flat_log = kKinova + "logs/Trajectory1.csv.gz";  // 1.94 s, every sensor 0
  const std::string run_log = kKinova + "logs/RunTrajectory1.csv.gz";
  const std::string flat = "Trajectory1.csv.gz: flat (range < 0.05 N*m) on joints 1-7";

  const CliResult identify =
      box.tpf("identify --quiet --log " + flat_log + robot + " --out p.json");
  EXPECT_EQ(identify.exit_code, 0) << identify.err;
  expect_contains(identify, flat);
  expect_contains(identify, "note: nothing is held out");
  expect_contains(identify, "this log spans 1.94 s");

  const CliResult diagnose = box.tpf("diagnose --quiet --log " + flat_log + robot);
  EXPECT_EQ(diagnose.exit_code, 0) << diagnose.err;
  expect_contains(diagnose, flat);
  expect_contains(diagnose, "No candidate effect can be claimed: nothing is held out");
  EXPECT_EQ(diagnose.out.find("none lowers the held-out residual"), std::string::npos)
      << diagnose.out;

  const CliResult train =
      box.tpf("train --quiet --log " + run_log + " --log " + flat_log + " --params p.json" + robot +
              " --per-joint --max-epochs 1 --out w.json");
  EXPECT_EQ(train.exit_code, 0) << train.err;
  expect_contains(train, flat);
  expect_contains(train, "RunTrajectory1.csv.gz: flat (range < 0.05 N*m) on joints 7");

  const CliResult validate = box.tpf("validate --params p.json --log " + flat_log + robot);
  EXPECT_EQ(validate.exit_code, 0) << validate.err;
  expect_contains(validate, flat);
}

}  // namespace
}  // namespace tpf::test
