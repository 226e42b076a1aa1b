// The `tpf` command line refuses, before any work, what would destroy an input or run on a
// meaningless number: an output that is the same file as an input (or as another output), a
// numeric option that is NaN, infinite or out of its range, and a directory where a file is
// expected. Each refusal names the option(s) and leaves every file as it was.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cli_runner.hpp"

namespace tpf::test {
namespace {

const std::string kRobot = " --robot " + kShippedData + "/arm4.robot.json";

/// Writes into `box` a 3 s twin log (log.csv), the shipped parameter file (p.json), a scenario
/// (s.json) and a foreign CSV for `tpf import` (k.csv, 7 joints, 5 rows).
void write_inputs(const CliSandbox& box) {
  box.write("s.json", "{\"kind\": \"excitation\", \"duration_s\": 3}");
  EXPECT_EQ(box.tpf("simulate --quiet --scenario s.json --out log.csv").exit_code, 0);
  std::filesystem::copy_file(kShippedData + "/arm4.params.json", box / "p.json");
  std::string header = "Time";
  for (const char* column : {"Position", "Velocity", "Cur", "Torque", "TorqueCur", "Temp"})
    for (int j = 1; j <= 7; ++j)
      header += std::string(",") + column + std::to_string(j);
  std::string rows;
  for (int r = 0; r < 5; ++r) {
    rows += std::to_string(r);
    for (int c = 0; c < 42; ++c)
      rows += ",0.1";
    rows += "\n";
  }
  box.write("k.csv", header + "\n" + rows);
}

/// The contents of every file in the sandbox, by name.
std::map<std::string, std::string> snapshot(const CliSandbox& box) {
  std::map<std::string, std::string> files;
  for (const std::string& name : box.files())
    if (std::filesystem::is_regular_file(box / name)) files[name] = CliSandbox::slurp(box / name);
  return files;
}

/// Expects a refusal before any work: exit 1, one line naming both options and the same file,
/// and the sandbox exactly as it was (inputs untouched, nothing written).
void expect_same_file_refused(const CliSandbox& box, const std::string& args,
                              const std::string& output, const std::string& other) {
  SCOPED_TRACE(args);
  const auto before = snapshot(box);
  const CliResult r = box.tpf(args, "", 30);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(line_count(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(output + " is the same file as " + other), std::string::npos) << r.err;
  EXPECT_TRUE(snapshot(box) == before) << "a file was changed or written";
}

TEST(CliOptionChecks, IdentifyRefusesAnOutputThatIsItsLog) {
  CliSandbox box("identify_same_file");
  write_inputs(box);
  const std::string log = CliSandbox::slurp(box / "log.csv");
  const CliResult r = box.tpf("identify --quiet --log log.csv" + kRobot + " --out log.csv");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("tpf identify: --out log.csv is the same file as --log log.csv: it would "
                       "overwrite the input; choose another output path"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(CliSandbox::slurp(box / "log.csv") == log) << "log.csv was overwritten";
  // Spelled otherwise, through a symbolic link or a hard link: still the same file.
  expect_same_file_refused(box, "identify --quiet --log log.csv" + kRobot + " --out ./x/../log.csv",
                           "--out ./x/../log.csv", "--log log.csv");
  std::filesystem::create_symlink("log.csv", box / "link.csv");
  expect_same_file_refused(box, "identify --quiet --log link.csv" + kRobot + " --out log.csv",
                           "--out log.csv", "--log link.csv");
  std::filesystem::create_hard_link(box / "log.csv", box / "hard.csv");
  expect_same_file_refused(box, "identify --quiet --log hard.csv" + kRobot + " --out log.csv",
                           "--out log.csv", "--log hard.csv");
}

TEST(CliOptionChecks, EveryWritingCommandRefusesAnOutputThatIsAnInputOrAnotherOutput) {
  CliSandbox box("same_file");
  write_inputs(box);
  const std::string map = " --map " + kShippedData + "/real/kinova-gen3/kinova.import.json";
  std::filesystem::create_directory(box / "ev");
  std::filesystem::copy_file(box / "log.csv", box / "ev/evaluation.json");
  const std::vector<std::vector<std::string>> cases = {
      {"simulate --quiet --scenario s.json --out s.json", "--out s.json", "--scenario s.json"},
      {"diagnose --quiet --log log.csv" + kRobot + " --json log.csv", "--json log.csv",
       "--log log.csv"},
      {"diagnose --quiet --log log.csv" + kRobot + " --json d.json --params ./d.json",
       "--params ./d.json", "--json d.json"},
      {"train --quiet --log log.csv --params p.json --out p.json", "--out p.json",
       "--params p.json"},
      {"train --quiet --log log.csv --params p.json --out w.json --checkpoint ./w.json",
       "--checkpoint ./w.json", "--out w.json"},
      {"calibrate --log log.csv --params p.json --out p.json", "--out p.json", "--params p.json"},
      {"validate --params p.json" + kRobot + " --log log.csv --json p.json", "--json p.json",
       "--params p.json"},
      {"evaluate --quiet --params p.json --calibration ev/evaluation.json --excitation log.csv "
       "--out ev",
       "--out ev/evaluation.json", "--calibration ev/evaluation.json"},
      {"import" + map + " --out k.csv k.csv", "--out k.csv", "the input k.csv"},
      {"import" + map + " --no-gzip --out-dir . k.csv", "the --out-dir file ./k.csv",
       "the input k.csv"},
      {"upgrade --params p.json --estimator ./p.json", "--estimator ./p.json", "--params p.json"},
  };
  for (const auto& c : cases)
    expect_same_file_refused(box, c[0], c[1], c[2]);
}

/// Each command's arguments without the option under test, on the inputs of write_inputs.
const std::map<std::string, std::string>& valid_arguments() {
  static const std::map<std::string, std::string> arguments = {
      {"simulate", "simulate --quiet --scenario s.json --out out.csv"},
      {"identify", "identify --quiet --log log.csv" + kRobot + " --out out.csv"},
      {"diagnose", "diagnose --quiet --log log.csv" + kRobot + " --json out.csv"},
      {"validate", "validate --params p.json" + kRobot + " --log log.csv --json out.csv"},
      {"train", "train --quiet --log log.csv --params p.json --out out.csv"},
      {"calibrate", "calibrate --log log.csv --params p.json --out out.csv"},
      {"evaluate",
       "evaluate --quiet --params p.json --calibration log.csv --excitation log.csv --out out.csv"},
      {"demo", "demo --no-measured --out out.csv"},
  };
  return arguments;
}

/// Runs each {command, option, value} of `cases`: refused before any work (nothing written),
/// "<option>: <value> is ...; expected ...".
void expect_values_refused(const std::vector<std::vector<std::string>>& cases) {
  CliSandbox box("bad_numbers");
  write_inputs(box);
  for (const auto& c : cases) {
    const std::string args = valid_arguments().at(c[0]) + " " + c[1] + " " + c[2];
    SCOPED_TRACE(args);
    const CliResult r = box.tpf(args, "", 30);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(r.err.rfind(c[1] + ": " + c[2] + " is ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("; expected"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(box / "out.csv"));
  }
}

// Each of these ran before, most of them on a default or the scenario's value instead.
TEST(CliOptionChecks, FittingCommandsRefuseNumbersOutOfRangeOrNotFinite) {
  expect_values_refused({
      {"simulate", "--duration", "nan"},
      {"simulate", "--duration", "0"},
      {"simulate", "--duration", "1e300"},
      {"simulate", "--seed", "-1"},
      {"identify", "--static-velocity", "0"},
      {"identify", "--static-velocity", "nan"},
      {"validate", "--static-velocity", "-1e-4"},
      {"diagnose", "--static-velocity", "nan"},
      {"diagnose", "--min-improvement", "1"},
      {"diagnose", "--min-improvement", "-0.1"},
      {"diagnose", "--min-improvement", "nan"},
  });
  // In range, the same options still run.
  CliSandbox box("good_numbers");
  box.write("s.json", "{\"kind\": \"excitation\", \"duration_s\": 600}");
  EXPECT_EQ(box.tpf(valid_arguments().at("simulate") + " --duration 0.5 --seed 0").exit_code, 0);
}

TEST(CliOptionChecks, TrainingAndEvaluationCommandsRefuseNumbersOutOfRangeOrNotFinite) {
  expect_values_refused({
      {"train", "--rest-weight", "nan"},
      {"train", "--rest-weight", "-1"},
      {"train", "--break-away-weight", "inf"},
      {"train", "--patience", "-1"},
      {"train", "--epoch-windows", "-1"},
      {"train", "--max-seconds", "nan"},
      {"train", "--max-epochs", "0"},
      {"train", "--min-learning-rate", "-1e-5"},
      {"train", "--split-cutoff", "200"},
      {"train", "--threads", "0"},
      {"train", "--joint-hidden", "8"},
      {"evaluate", "--teaching-duration", "0"},
      {"evaluate", "--teaching-duration", "nan"},
      {"calibrate", "--pad-gain", "nan"},
      {"calibrate", "--pad-gain", "inf"},
      {"demo", "--train-duration", "0"},
      {"demo", "--test-duration", "nan"},
      {"demo", "--train-safety-seconds", "-1"},
      {"demo", "--joint-hidden", "64"},
  });
}

TEST(CliOptionChecks, DirectoryWhereAFileIsExpectedIsNamed) {
  CliSandbox box("directory");
  write_inputs(box);
  std::filesystem::create_directory(box / "dir");
  const std::string validate = "validate --params p.json" + kRobot + " --log log.csv";
  const std::string calibrate = "calibrate --log log.csv --params p.json --out e.json";
  // {arguments, the option given the directory}
  const std::vector<std::pair<std::string, std::string>> cases = {
      {validate + " --weights dir", "--weights"},
      {validate + " --estimator dir", "--estimator"},
      {calibrate + " --pads dir", "--pads"},
      {calibrate + " --weights dir", "--weights"},
      {"upgrade --params p.json --weights dir", "--weights"},
  };
  for (const auto& [args, option] : cases) {
    SCOPED_TRACE(args);
    const CliResult r = box.tpf(args);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(r.err.rfind(option + ": dir is a directory, not a file", 0), 0u) << r.err;
  }
  // An output that is a directory was found only at the write, after the work.
  const CliResult out = box.tpf("identify --quiet --log log.csv" + kRobot + " --out dir");
  EXPECT_NE(out.exit_code, 0);
  EXPECT_NE(out.err.find("tpf identify: --out dir is a directory"), std::string::npos) << out.err;
  // "none" is still a --pads value.
  EXPECT_EQ(box.tpf(calibrate + " --pads none").exit_code, 0);
}

TEST(CliOptionChecks, QuietReplayingCommandsStillSayWhatTheReaderSkipped) {
  CliSandbox box("quiet_notes");
  write_inputs(box);
  std::string log = CliSandbox::slurp(box / "log.csv");
  ASSERT_EQ(log.back(), '\n');
  log.pop_back();  // a cut file: its last row without a newline
  box.write("cut.csv", log);
  const std::string evaluate = "evaluate --quiet --params p.json --calibration log.csv --out ev";
  const CliResult cut = box.tpf(evaluate + " --excitation cut.csv");
  EXPECT_EQ(cut.exit_code, 0) << cut.err;
  EXPECT_NE(cut.err.find("log cut.csv: "), std::string::npos) << cut.err;
  EXPECT_NE(cut.err.find("(1 more skipped)"), std::string::npos) << cut.err;
  EXPECT_NE(cut.err.find("the file ends without a newline"), std::string::npos) << cut.err;
  // Whole logs are not mentioned with --quiet.
  const CliResult whole = box.tpf(evaluate + " --excitation log.csv");
  EXPECT_EQ(whole.exit_code, 0) << whole.err;
  EXPECT_EQ(whole.err.find("log log.csv"), std::string::npos) << whole.err;
}

}  // namespace
}  // namespace tpf::test
