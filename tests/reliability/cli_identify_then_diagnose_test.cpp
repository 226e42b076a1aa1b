// `tpf diagnose --identify-out`: identify and diagnose in one run on one reading of the log give
// the files and the printout of the two commands run apart, byte for byte.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

#include "cli_runner.hpp"

namespace tpf::test {
namespace {

// The "(… s)" wall time identify prints after the file name.
std::string without_wall_time(const std::string& text) {
  return std::regex_replace(text, std::regex(R"( \([0-9.]+ s\))"), "");
}

TEST(CliIdentifyThenDiagnose, GivesTheFilesAndPrintoutOfBothCommands) {
  CliSandbox box("identify_then_diagnose");
  const std::string robot = " --robot " + kShippedData + "/bench1.robot.json";
  // A static threshold other than the default: both fits must take it.
  const std::string fit = " --log log.csv" + robot + " --static-velocity 2e-4";
  ASSERT_EQ(box.tpf("simulate --scenario " + kShippedData +
                    "/scenarios/bench1-excitation.json --seed 3 --duration 20 --out log.csv")
                .exit_code,
            0);

  const CliResult identify = box.tpf("identify" + fit + " --out p.json");
  ASSERT_EQ(identify.exit_code, 0) << identify.err;
  const CliResult diagnose = box.tpf("diagnose" + fit + " --json d.json --params pd.json");
  ASSERT_EQ(diagnose.exit_code, 0) << diagnose.err;
  const CliResult both =
      box.tpf("diagnose" + fit + " --json d2.json --params pd2.json --identify-out p2.json");
  ASSERT_EQ(both.exit_code, 0) << both.err;

  EXPECT_EQ(CliSandbox::slurp(box / "p2.json"), CliSandbox::slurp(box / "p.json"));
  EXPECT_EQ(CliSandbox::slurp(box / "d2.json"), CliSandbox::slurp(box / "d.json"));
  EXPECT_EQ(CliSandbox::slurp(box / "pd2.json"), CliSandbox::slurp(box / "pd.json"));
  // identify's printout, then diagnose's (the file names aside).
  std::string expected = without_wall_time(identify.out + diagnose.out);
  for (const std::string name : {"p", "d", "pd"})
    expected = std::regex_replace(expected, std::regex("wrote " + name + "\\.json"),
                                  "wrote " + name + "2.json");
  EXPECT_EQ(without_wall_time(both.out), expected);
  // The progress of both passes, identify's first.
  EXPECT_LT(both.err.find("identify: pass 3/3"), both.err.find("diagnose: pass 1/4")) << both.err;
  // Not a vacuous comparison: a diagnosis that wrote an effect (its verdict table's "yes"), and
  // identify's table.
  EXPECT_NE(both.out.find("  yes  "), std::string::npos) << both.out;
  EXPECT_NE(both.out.find("held-out residual RMSE"), std::string::npos) << both.out;

  // One file for two outputs is refused before the log is read, naming the file and the options.
  const CliResult shared =
      box.tpf("diagnose --quiet" + fit + " --params ./same.json --identify-out same.json");
  EXPECT_EQ(shared.exit_code, 1);
  EXPECT_NE(shared.err.find("--identify-out same.json is the same file as --params ./same.json"),
            std::string::npos)
      << shared.err;
  EXPECT_FALSE(std::filesystem::exists(box / "same.json"));

  // identify's friction options reach the one run's fit; without --identify-out they are
  // refused, naming both options.
  const std::string options = " --no-load-friction --friction-from-sensor";
  ASSERT_EQ(box.tpf("identify --quiet" + fit + options + " --out p3.json").exit_code, 0);
  const CliResult both_options =
      box.tpf("diagnose --quiet" + fit + options + " --identify-out p4.json");
  ASSERT_EQ(both_options.exit_code, 0) << both_options.err;
  EXPECT_EQ(CliSandbox::slurp(box / "p4.json"), CliSandbox::slurp(box / "p3.json"));
  EXPECT_NE(CliSandbox::slurp(box / "p4.json"), CliSandbox::slurp(box / "p.json"));
  const CliResult alone = box.tpf("diagnose --quiet" + fit + " --no-load-friction");
  EXPECT_NE(alone.exit_code, 0);
  EXPECT_NE(alone.err.find("--no-load-friction requires --identify-out"), std::string::npos)
      << alone.err;

  // An identify file that cannot be written is named (identify's own error).
  const CliResult unwritable = box.tpf("diagnose --quiet" + fit + " --identify-out missing/p.json");
  EXPECT_EQ(unwritable.exit_code, 1);
  EXPECT_NE(unwritable.err.find("missing/p.json"), std::string::npos) << unwritable.err;
}

}  // namespace
}  // namespace tpf::test
