// Every command's default printout fits a screen (≤ 40 lines, stdout and stderr together, a
// progress line redrawn with '\r' counted once), and --verbose, where a command has it, prints
// more: the built `tpf` on short twin logs.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace tpf::test {
namespace {

constexpr int kScreenLines = 40;

/// Lines of a run's output as a terminal shows them: lines end at '\n' only, so a progress line
/// redrawn with '\r' ("a\rb\rc\n") counts once.
int screen_lines(const CliResult& r) {
  return line_count(r.out) + line_count(r.err);
}

struct CommandRun {
  std::string name;  ///< what the failure message names
  std::string args;  ///< the default run
  bool verbose;      ///< the command has --verbose (it must print more)
};

TEST(CliPrintout, EveryCommandsDefaultFitsAScreenAndVerbosePrintsMore) {
  CliSandbox box("printout");
  const std::string d = kShippedData + "/";
  const std::string robot = " --robot " + d + "arm4.robot.json";
  const std::string model = " --params " + d + "arm4.params.json";
  const std::string weights = " --weights " + d + "weights/arm4.tcn.json";
  const std::string foreign = [] {
    std::string csv = "Time,P1,P2,V1,V2,C1,C2\n";
    for (int k = 0; k < 200; ++k) {
      const double t = 0.01 * k;
      csv += std::to_string(t) + "," + std::to_string(0.1 * t) + ",0.5,0.1,0," +
             std::to_string(0.01 * k) + ",0.2\n";
    }
    return csv;
  }();
  std::string recordings;  // six recordings of the same foreign file
  for (int k = 1; k <= 6; ++k) {
    box.write("foreign" + std::to_string(k) + ".csv", foreign);
    recordings += " foreign" + std::to_string(k) + ".csv";
  }
  box.write("map.json",
            R"({"format": "tpf-import", "version": 1, "joints": 2,
 "time": {"column": "Time", "unit": "s"},
 "columns": {"q": {"source": "P{j}", "unit": "rad"}, "dq": {"source": "V{j}", "unit": "rad/s"},
             "i": {"source": "C{j}", "unit": "A"}},
 "metadata": {"robot": "two-joint test", "source": "synthetic", "license": "CC0"}})");
  const std::string scenarios = " --scenario " + d + "scenarios/";
  const std::string kinova = d + "real/kinova-gen3/logs/";
  const std::string gen3 = " --robot " + d + "real/kinova-gen3/gen3.robot.json";
  const std::string gen3_fitting = " " + kinova + "RunTrajectory1.csv.gz " + kinova +
                                   "Trajectory1.csv.gz " + kinova +
                                   "RecordTrajectory_quadratic.csv.gz";
  const std::vector<CommandRun> runs{
      {"simulate", "simulate" + scenarios + "excitation.json --seed 1 --duration 40 --out ex.csv",
       false},
      {"simulate contacts",
       "simulate" + scenarios + "static-contacts.json --seed 4 --duration 30 --out c.csv", false},
      {"info", "info", false},
      {"identify", "identify --log ex.csv" + robot + " --out id.params.json", true},
      {"diagnose", "diagnose --log ex.csv" + robot + " --report d.html", true},
      {"validate", "validate --params id.params.json" + robot + " --log c.csv" + weights, false},
      {"train", "train --log ex.csv" + model + " --per-joint --max-epochs 3 --out t.tcn.json",
       true},
      {"calibrate", "calibrate --log ex.csv" + model + weights + " --out e.json", false},
      {"evaluate",
       "evaluate" + model + weights +
           " --calibration ex.csv --excitation ex.csv --contacts c.csv "
           "--out report",
       true},
      {"estimate",
       "estimate --log c.csv" + model + " --estimator e.json" + weights + " --out c.est.csv", true},
      {"import", "import --map map.json --out-dir imported" + recordings, true},
      {"upgrade", "upgrade --params old.params.json", false},
      // 7 joints with torque sensors (MEASURED, Kinova Gen3): the sensor tables fit too.
      {"identify measured", "identify --quiet --log" + gen3_fitting + gen3 + " --out gen3.json",
       true},
      {"validate measured",
       "validate --params gen3.json" + gen3 + " --log " + kinova + "opti_traj_testing1.csv.gz " +
           kinova + "opti_traj_testing2.csv.gz",
       true},
  };
  for (const CommandRun& run : runs) {
    SCOPED_TRACE(run.name);
    if (run.name == "upgrade") {  // a version-1 file of the identified model, efforts 1:1 in mA
      auto old = nlohmann::json::parse(CliSandbox::slurp(box / "id.params.json"));
      old["version"] = 1;
      old.erase("torque_unit");
      old["effort_unit"] = "mA";
      old["effort_per_newton_metre"] = std::vector<double>(4, 1.0);
      box.write("old.params.json", old.dump());
    }
    const CliResult r = box.tpf(run.args);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_LE(screen_lines(r), kScreenLines) << r.out << r.err;
    EXPECT_GE(screen_lines(r), 1);
    if (!run.verbose) continue;
    const CliResult v = box.tpf(run.args + " --verbose");
    ASSERT_EQ(v.exit_code, 0) << v.err;
    EXPECT_GT(screen_lines(v), screen_lines(r)) << r.out << "\n--verbose:\n" << v.out;
  }
}

}  // namespace
}  // namespace tpf::test
