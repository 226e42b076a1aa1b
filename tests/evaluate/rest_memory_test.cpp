// The friction memory at rest against the noise floor, on sequences whose noise and memory are
// known.
#include "offline/evaluate/rest_memory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tpf::offline {
namespace {

constexpr double kRestRate = 400.0;

/// One joint: stretches of 2 s at rest, each holding a different constant (the memory of the
/// last motion, ±memory), separated by 0.5 s of motion; white noise σ on the nominal residual at
/// rest, and the compensated residual = noise + a share `left` of the memory.
ResidualRecording rest_recording(double sigma, double memory, double left, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma);
  const int stretches = 40, rest = 800, motion = 200, T = stretches * (rest + motion);
  ResidualRecording r;
  r.t = Eigen::VectorXd::LinSpaced(T, 0.0, (T - 1) / kRestRate);
  r.dq = Eigen::MatrixXd::Zero(T, 1);
  r.nominal.resize(T, 1);
  r.compensated.resize(T, 1);
  for (int s = 0; s < stretches; ++s) {
    const double held = (s % 2 == 0 ? 1.0 : -1.0) * memory;
    for (int k = 0; k < rest + motion; ++k) {
      const int row = s * (rest + motion) + k;
      const bool moving = k >= rest;
      const double n = noise(rng);
      r.dq(row, 0) = moving ? 0.3 : 0.0;
      r.nominal(row, 0) = moving ? 50.0 : held + n;
      r.compensated(row, 0) = moving ? 50.0 : left * held + n;
    }
  }
  return r;
}

TEST(RestMemory, NoiseFloorIsTheWhiteNoiseUnderAHeldMemory) {
  // The memory (200) is 33× the noise (6): the floor must see the noise only.
  const std::vector<ResidualRecording> recs{rest_recording(6.0, 200.0, 0.1, 1)};
  const Eigen::VectorXd floor = rest_noise_floor(recs);
  ASSERT_EQ(floor.size(), 1);
  EXPECT_NEAR(floor[0], 6.0, 0.1);  // 32 000 pairs: the estimate's spread ≈ 0.4 %
}

TEST(RestMemory, SplitsTheStaticRmseIntoFloorAndMemory) {
  const std::vector<ResidualRecording> recs{rest_recording(6.0, 200.0, 0.1, 2)};
  const std::vector<ResidualRow> table = residual_table(recs, Eigen::VectorXd::Constant(1, 2.0));
  const std::vector<RestMemoryRow> rows = rest_memory(table, rest_noise_floor(recs));
  ASSERT_EQ(rows.size(), 1u);
  const RestMemoryRow& m = rows[0];
  EXPECT_EQ(m.joint, 0);
  EXPECT_NEAR(m.nominal_memory, 200.0, 1.0);
  EXPECT_NEAR(m.compensated_memory, 20.0, 0.5);
  EXPECT_NEAR(m.removed_share, 0.9, 0.005);
  // RMSE² = memory² + floor² (both from the same rows).
  EXPECT_NEAR(m.compensated_rmse * m.compensated_rmse,
              m.compensated_memory * m.compensated_memory + m.noise_floor * m.noise_floor,
              0.05 * m.noise_floor * m.noise_floor);
  EXPECT_NEAR(m.compensated_times_floor, std::hypot(20.0, 6.0) / 6.0, 0.1);
}

TEST(RestMemory, ACompensatorAtTheFloorRemovesAllOfTheMemory) {
  const std::vector<ResidualRecording> recs{rest_recording(6.0, 150.0, 0.0, 3)};
  const std::vector<RestMemoryRow> rows =
      rest_memory(residual_table(recs, Eigen::VectorXd::Constant(1, 2.0)), rest_noise_floor(recs));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_GT(rows[0].removed_share, 0.97);
  EXPECT_NEAR(rows[0].compensated_times_floor, 1.0, 0.03);
}

TEST(RestMemory, AJointThatNeverRestsHasNoFloor) {
  ResidualRecording r = rest_recording(6.0, 100.0, 0.5, 4);
  r.dq.setConstant(0.3);
  const Eigen::VectorXd floor = rest_noise_floor({r});
  EXPECT_TRUE(std::isnan(floor[0]));
}

}  // namespace
}  // namespace tpf::offline
