// The error floor of a motion model against the sensor: the residual's RMS above a cut-off,
// filtered within each file.
#include "offline/measured_study/noise_floor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace tpf::offline {
namespace {

// Two files of 4 s at 1 kHz, times restarting in each file.
Log two_files(Eigen::VectorXd& t) {
  Log log;
  log.columns = {"t"};
  log.values = Eigen::MatrixXd::Zero(8000, 1);
  log.file_starts = {0, 4000};
  t.resize(8000);
  for (Eigen::Index k = 0; k < 8000; ++k)
    t[k] = 1e-3 * static_cast<double>(k % 4000);
  return log;
}

TEST(NoiseFloor, SlowSignalHasNoFloorAndWhiteNoiseKeepsNearlyAllOfIt) {
  Eigen::VectorXd t;
  const Log log = two_files(t);
  Eigen::MatrixXd x(8000, 2);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (Eigen::Index k = 0; k < 8000; ++k) {
    x(k, 0) = 2.0 * std::sin(2 * M_PI * 0.5 * t[k]) + (k < 4000 ? 5.0 : -5.0);  // file offsets
    x(k, 1) = noise(rng);
  }
  x(10, 1) = std::numeric_limits<double>::quiet_NaN();  // a NaN is skipped, not spread
  const std::vector<double> floor = high_frequency_rms(log, t, x, 20.0);
  ASSERT_EQ(floor.size(), 2u);
  // A 0.5 Hz sine with a different offset per file: nothing above 20 Hz (a filter run across
  // the files' boundary would turn the 10 N·m step into a burst there).
  EXPECT_LT(floor[0], 2e-3);
  // White noise of σ = 1 at 1 kHz: above 20 Hz lies ≈ 1 − 2·20/1000 of its power.
  EXPECT_GT(floor[1], 0.95);
  EXPECT_LT(floor[1], 1.02);
  const std::vector<double> all = finite_rms_per_column(x.rightCols(1));
  EXPECT_NEAR(all[0], 1.0, 0.03);
  EXPECT_GE(all[0], floor[1]);
}

TEST(NoiseFloor, BandsSplitTheRmsAtBothCutOffs) {
  Eigen::VectorXd t;
  const Log log = two_files(t);
  Eigen::MatrixXd x(8000, 1);
  for (Eigen::Index k = 0; k < 8000; ++k)  // 2 N·m at 0.5 Hz, 1 at 6 Hz, 0.5 at 97 Hz
    x(k, 0) = 2.0 * std::sin(2 * M_PI * 0.5 * t[k]) + std::sin(2 * M_PI * 6.0 * t[k]) +
              0.5 * std::sin(2 * M_PI * 97.0 * t[k]);
  const BandRms b = band_rms(log, t, x, 2.0, 20.0);
  EXPECT_NEAR(b.low[0], 2.0 / std::sqrt(2.0), 0.05);
  EXPECT_NEAR(b.mid[0], 1.0 / std::sqrt(2.0), 0.05);
  EXPECT_NEAR(b.high[0], 0.5 / std::sqrt(2.0), 0.02);
  EXPECT_NEAR(b.low[0] * b.low[0] + b.mid[0] * b.mid[0] + b.high[0] * b.high[0],
              b.total[0] * b.total[0], 1e-9);
}

TEST(NoiseFloor, ColumnWithoutFiniteSamplesIsNaN) {
  Eigen::VectorXd t;
  const Log log = two_files(t);
  const Eigen::MatrixXd x =
      Eigen::MatrixXd::Constant(8000, 1, std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(std::isnan(high_frequency_rms(log, t, x, 20.0)[0]));
  EXPECT_TRUE(std::isnan(finite_rms_per_column(x)[0]));
}

}  // namespace
}  // namespace tpf::offline
