// The current low-pass's time constant: pooled, a file whose current carries a large oscillation
// the sensor does not show chooses a filter whose lag ruins the other file; the worst-file
// criterion takes the one that helps both. Numbers from the first-order filter's response.
#include "offline/measured_study/low_pass_choice.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tpf::offline {
namespace {

// Two files of 4 s at 1 kHz. Joint 1: the sensor reads 10·sin(2π·0.5 t) in both; file A's
// current adds 0.5 N·m at 97 Hz, file B's 6 N·m at 6 Hz. Joint 2: no sensor (NaN residual).
struct TwoFiles {
  Log log;
  JointSamples samples;
  Eigen::MatrixXd residual;
};

TwoFiles two_files_with_an_oscillation() {
  TwoFiles f;
  const Eigen::Index n = 8000;
  f.log.columns = {"t"};
  f.log.values = Eigen::MatrixXd::Zero(n, 1);
  f.log.file_starts = {0, 4000};
  f.samples.t.resize(n);
  f.samples.effort = Eigen::MatrixXd::Zero(n, 2);
  f.residual = Eigen::MatrixXd::Constant(n, 2, std::numeric_limits<double>::quiet_NaN());
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = 1e-3 * static_cast<double>(k % 4000);
    const double sensor = 10.0 * std::sin(2 * M_PI * 0.5 * t);
    const double extra =
        k < 4000 ? 0.5 * std::sin(2 * M_PI * 97.0 * t) : 6.0 * std::sin(2 * M_PI * 6.0 * t);
    f.samples.t[k] = t;
    f.samples.effort(k, 0) = sensor + extra;
    f.samples.effort(k, 1) = sensor;
    f.residual(k, 0) = extra;  // K_t·i − d − τ_sensor with d = 0
  }
  return f;
}

TEST(LowPassChoice, PooledLetsTheOscillatingFileChooseWorstFileHelpsBoth) {
  const TwoFiles f = two_files_with_an_oscillation();
  const LowPassChoice pooled =
      choose_current_low_pass(f.log, f.samples, f.residual, LowPassCriterion::kPooled);
  // Pooled RMSE over the candidates: 3.010 unfiltered, 2.816 at 10 ms, 1.763 at 50 ms, 2.167 at
  // 100 ms; at 50 ms file A's error is 1.066 against 0.354 unfiltered (the lag of the 0.5 Hz load).
  EXPECT_DOUBLE_EQ(pooled.time_constant[0], 0.05);
  EXPECT_NEAR(pooled.rmse[0], 1.763, 0.01);
  EXPECT_NEAR(pooled.worst_ratio[0], 3.015, 0.02);
  const LowPassChoice worst =
      choose_current_low_pass(f.log, f.samples, f.residual, LowPassCriterion::kWorstFile);
  // 10 ms: file A 0.218 (from 0.354), file B 3.976 (from 4.243); 20 ms already hurts A (0.430).
  EXPECT_DOUBLE_EQ(worst.time_constant[0], 0.01);
  EXPECT_NEAR(worst.worst_ratio[0], 3.976 / 4.243, 0.005);
  EXPECT_NEAR(worst.rmse[0], 2.816, 0.01);
  // A joint without a residual: no filter, no numbers.
  EXPECT_EQ(worst.time_constant[1], 0.0);
  EXPECT_TRUE(std::isnan(worst.rmse[1]));
  EXPECT_TRUE(std::isnan(pooled.worst_ratio[1]));
}

TEST(LowPassChoice, LowPassedResidualRestartsAtEachFile) {
  const TwoFiles f = two_files_with_an_oscillation();
  const Eigen::MatrixXd r =
      low_passed_residual(f.log, f.samples, f.residual, Eigen::Vector2d(0.05, 0.05));
  // The filter restarts (y = x) at each file's first row: no step carried across files.
  EXPECT_DOUBLE_EQ(r(4000, 0), f.residual(4000, 0));
  EXPECT_DOUBLE_EQ(r(0, 0), f.residual(0, 0));
  EXPECT_TRUE(std::isnan(r(10, 1)));
  const LowPassChoice pooled =
      choose_current_low_pass(f.log, f.samples, f.residual, LowPassCriterion::kPooled);
  double sum = 0;
  for (Eigen::Index k = 0; k < r.rows(); ++k)
    sum += r(k, 0) * r(k, 0);
  EXPECT_NEAR(std::sqrt(sum / static_cast<double>(r.rows())), pooled.rmse[0], 1e-12);
}

}  // namespace
}  // namespace tpf::offline
