// tpf train on a log whose clock jitters (a mobile manipulator's ~100 Hz with steps of 7–12 ms):
// the networks take the rows as they come, and train says so with the counts; a log of a regular
// clock gets no such line. (The twin's own logs jitter too: its host clock.)
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "cli_runner.hpp"
#include "offline/log/log_writer.hpp"
#include "offline/log/read_log.hpp"

namespace tpf::test {
namespace {

TEST(CliTrainSteps, AJitteredClockIsSaidAndARegularOneIsNot) {
  CliSandbox box("train_steps");
  const std::string d = kShippedData + "/";
  ASSERT_EQ(box.tpf("simulate --scenario " + d +
                    "scenarios/excitation.json --seed 1 --duration 20 --out ex.csv")
                .exit_code,
            0);
  offline::Log log = offline::read_log(box / "ex.csv");
  const int t = log.column("t");
  ASSERT_GE(t, 0);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(0.77, 1.23);  // steps of 0.77–1.23 × nominal
  const double step = log.values(1, t) - log.values(0, t);
  for (Eigen::Index k = 1; k < log.values.rows(); ++k)
    log.values(k, t) = log.values(k - 1, t) + step * jitter(rng);
  offline::write_log(box / "jitter.csv", log);
  for (Eigen::Index k = 0; k < log.values.rows(); ++k)  // a regular clock: no step off
    log.values(k, t) = step * static_cast<double>(k);
  offline::write_log(box / "regular.csv", log);

  const std::string train = " --params " + d + "arm4.params.json --per-joint --max-epochs 1";
  const CliResult jittered = box.tpf("train --log jitter.csv" + train + " --out j.tcn.json");
  ASSERT_EQ(jittered.exit_code, 0) << jittered.err;
  EXPECT_NE(jittered.out.find("time steps are off the median"), std::string::npos) << jittered.out;
  EXPECT_NE(jittered.out.find("not resampled"), std::string::npos) << jittered.out;
  const CliResult regular = box.tpf("train --log regular.csv" + train + " --out r.tcn.json");
  ASSERT_EQ(regular.exit_code, 0) << regular.err;
  EXPECT_EQ(regular.out.find("time steps are off the median"), std::string::npos) << regular.out;
}

}  // namespace
}  // namespace tpf::test
