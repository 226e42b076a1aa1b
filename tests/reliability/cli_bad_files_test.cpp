// The `tpf` binary under bad files: a one-line error naming the file and the place, a non-zero
// exit, and no output file (nor temporary) left behind — also when a write fails mid-run.
#include <gtest/gtest.h>

#include <csignal>

#include "cli_runner.hpp"

namespace tpf::test {
namespace {

/// A scenario of `seconds` on the shipped arm with the given extra JSON members.
std::string scenario_json(double seconds, const std::string& extra = "") {
  return "{\"kind\": \"excitation\", \"duration_s\": " + std::to_string(seconds) + extra + "}";
}

/// Expects a refused run: exit 1, one line "tpf: error: <file>...<place>...", nothing written.
void expect_refused(const CliSandbox& box, const CliResult& r, const std::string& file,
                    const std::string& place) {
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("tpf: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(file), std::string::npos) << "does not name " << file << ": " << r.err;
  EXPECT_NE(r.err.find(place), std::string::npos) << "does not name " << place << ": " << r.err;
  EXPECT_FALSE(std::filesystem::exists(box / "out.csv"));
  for (const std::string& name : box.files())
    EXPECT_EQ(name.find(".tmp."), std::string::npos) << "temporary left behind: " << name;
}

TEST(CliBadFiles, EmptyScenario) {
  CliSandbox box("empty_scenario");
  box.write("s.json", "");
  expect_refused(box, box.tpf("simulate --quiet --scenario s.json --out out.csv"), "s.json:1",
                 "not valid JSON");
}

TEST(CliBadFiles, ScenarioTruncatedMidLineNamesLineAndColumn) {
  CliSandbox box("truncated_scenario");
  box.write("s.json", "{\n  \"kind\": \"excitation\",\n  \"duration_s\": 1");
  expect_refused(box, box.tpf("simulate --quiet --scenario s.json --out out.csv"), "s.json",
                 "line 3");
}

TEST(CliBadFiles, ScenarioWithWrongKindUnknownKeyOrHugeValueNamesTheKey) {
  CliSandbox box("bad_scenario");
  box.write("kind.json", "{\"kind\": \"exitation\"}");
  expect_refused(box, box.tpf("simulate --quiet --scenario kind.json --out out.csv"), "kind.json",
                 "kind");
  box.write("key.json", scenario_json(1, ", \"sensors\": {\"current_noize_ma\": 1}"));
  expect_refused(box, box.tpf("simulate --quiet --scenario key.json --out out.csv"), "key.json",
                 "sensors.current_noize_ma");
  box.write("huge.json", scenario_json(1e300));
  expect_refused(box, box.tpf("simulate --quiet --scenario huge.json --out out.csv"), "huge.json",
                 "duration_s");
  // 1e999 overflows a double while parsing: was "tpf: unexpected error: [json.exception.
  // out_of_range.406] number overflow parsing '1e999'" with exit 2 and no file name.
  box.write("nan.json", "{\"kind\": \"excitation\",\n \"initial_q\": [0, 1e999, 0, 0]}");
  expect_refused(box, box.tpf("simulate --quiet --scenario nan.json --out out.csv"), "nan.json:2",
                 "1e999");
}

/// A robot file beside copies of the arm's pads, pointing at `urdf` (written beside it).
void write_robot(const CliSandbox& box, const std::string& urdf) {
  std::string robot = CliSandbox::slurp(kShippedData + "/arm4.robot.json");
  robot.replace(robot.find("\"arm4.urdf\""), 11, "\"bad.urdf\"");
  box.write("robot.json", robot);
  box.write("bad.urdf", urdf);
  std::filesystem::copy_file(kShippedData + "/arm4.pads.json", box / "arm4.pads.json");
}

/// The arm's URDF with `from` replaced by `to`.
std::string arm_urdf_with(const std::string& from, const std::string& to) {
  std::string urdf = CliSandbox::slurp(kShippedData + "/arm4.urdf");
  const auto at = urdf.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return urdf.replace(at, from.size(), to);
}

TEST(CliBadFiles, PlanarJointInTheRobotsUrdfStopsTheSimulationBeforeAnyOutput) {
  CliSandbox box("planar");
  write_robot(
      box, arm_urdf_with("name=\"joint3\" type=\"revolute\"", "name=\"joint3\" type=\"planar\""));
  box.write("s.json", scenario_json(1, ", \"robot\": \"robot.json\""));
  expect_refused(box, box.tpf("simulate --quiet --scenario s.json --out out.csv"), "bad.urdf",
                 "joint 'joint3'");
  expect_refused(box, box.tpf("info --robot robot.json"), "bad.urdf", "joint 'joint3'");
}

TEST(CliBadFiles, UrdfWithALoopIsRefusedNamingTheFile) {
  CliSandbox box("loop");
  // joint5 closes the chain: link5 → link1 gives link1 a second parent (a loop, not a tree).
  write_robot(box, arm_urdf_with("</robot>", R"(<joint name="joint5" type="revolute">
    <parent link="link5"/><child link="link1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>)"));
  expect_refused(box, box.tpf("info --robot robot.json"), "bad.urdf", "URDF");
}

TEST(CliBadFiles, MissingOutputFolderIsNamed) {
  CliSandbox box("no_folder");
  box.write("s.json", scenario_json(0.05));
  const CliResult r = box.tpf("simulate --quiet --scenario s.json --out missing/out.csv");
  expect_refused(box, r, "missing/out.csv", "cannot create");
}

TEST(CliBadFiles, WriteFailingMidRunLeavesTheOldOutputAndNoTemporary) {
  CliSandbox box("disk_full");
  box.write("s.json", scenario_json(20.0));
  box.write("out.csv", "previous contents\n");
  // 64 KiB file-size limit, SIGXFSZ ignored: the log write fails with EFBIG part-way through.
  const CliResult r =
      box.tpf("simulate --quiet --scenario s.json --out out.csv", "ulimit -f 64; trap '' XFSZ;");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("out.csv"), std::string::npos) << r.err;
  EXPECT_EQ(CliSandbox::slurp(box / "out.csv"), "previous contents\n");
  EXPECT_EQ(box.files(), (std::vector<std::string>{"out.csv", "s.json"}));
}

TEST(CliBadFiles, KilledRunLeavesNeitherOutputNorTemporary) {
  CliSandbox box("killed");
  box.write("s.json", scenario_json(600.0));
  // SIGTERM once the log is being written (its temporary exists), at most 60 s later. (A
  // non-interactive shell starts background jobs with SIGINT ignored, so Ctrl-C is not testable
  // this way; TERM ends the process the same way, without unwinding.)
  const CliResult r = box.sh(
      "\"$TPF\" simulate --quiet --scenario s.json --out out.csv & pid=$!; n=0; "
      "while [ $n -lt 600 ] && ! ls -A | grep -q '^.out.csv.tmp.'; do sleep 0.1; n=$((n+1)); done; "
      "kill -TERM $pid; wait $pid");
  EXPECT_EQ(r.exit_code, 128 + SIGTERM) << r.err;
  EXPECT_FALSE(std::filesystem::exists(box / "out.csv"));
  // Its signal handler removed the hidden temporary before the process ended by SIGTERM.
  EXPECT_EQ(box.files(), (std::vector<std::string>{"s.json"}));
}

// `tpf identify` and `tpf diagnose` on bad logs: the reader's error, one line, nothing written.
TEST(CliBadFiles, IdentifyAndDiagnoseNameTheLogAndTheLine) {
  CliSandbox box("bad_logs");
  const std::string head = "# tpf-log: 1\nt,q1,q2,q3,q4,dq1,dq2,dq3,dq4,i1,i2,i3,i4\n";
  const std::string row = "0,0,0,0,0,0,0,0,0,1,2,3,4\n";
  const std::string robot = kShippedData + "/arm4.robot.json";
  const std::vector<std::pair<std::string, std::string>> logs = {
      {"", "the file is empty"},
      {head + row + "0.0025,0,0,0,0,0,0,0,0,1,2,3,4,5", "log.csv:4: expected 13 fields, found 14"},
      {"# tpf-log: 2\n" + head.substr(13) + row, "log.csv:1: tpf-log: version 2"},
      {"t,q1\n0,1\n", "q"},  // wrong header: no joint columns
      {head + "0,0,0,0,0,0,0,0,0,1e400,2,3,4\n", "log.csv:3: i1: '1e400' is out of range"},
  };
  for (const auto& [text, place] : logs) {
    SCOPED_TRACE(place);
    box.write("log.csv", text);
    expect_refused(box,
                   box.tpf("identify --quiet --log log.csv --robot " + robot + " --out out.csv"),
                   "log.csv", place);
    expect_refused(box,
                   box.tpf("diagnose --quiet --log log.csv --robot " + robot +
                           " --json out.csv --params out.params.json"),
                   "log.csv", place);
  }
}

TEST(CliBadFiles, ALogOfAnotherArmNamesBothJointCounts) {
  // Was "arm4.urdf: the chain has 4 revolute joints, this program is built for 3": the robot
  // file blamed for the log's joint count.
  CliSandbox box("other_arm");
  box.write("log.csv", "# tpf-log: 1\nt,q1,q2,q3,dq1,dq2,dq3,i1,i2,i3\n0,0,0,0,0,0,0,1,2,3\n");
  const std::string robot = kShippedData + "/arm4.robot.json";
  for (const std::string& command : std::vector<std::string>{
           "identify --quiet --log log.csv --out out.csv --robot ",
           "diagnose --quiet --log log.csv --json out.csv --params out.params.json --robot ",
           "validate --log log.csv --params " + kShippedData + "/arm4.params.json --robot "})
    expect_refused(box, box.tpf(command + robot), "log.csv",
                   "the log has 3 joints (q1 … q3), the robot file " + robot + " has 4");
}

TEST(CliBadFiles, UnknownCommandAndMissingFileExitNonZero) {
  CliSandbox box("usage");
  EXPECT_NE(box.tpf("no-such-command").exit_code, 0);
  const CliResult r = box.tpf("simulate --scenario absent.json --out out.csv");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("absent.json"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(box / "out.csv"));
}

}  // namespace
}  // namespace tpf::test
