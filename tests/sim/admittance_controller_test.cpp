// The teaching host's goal reaches the drive as a first-order hold over the host cycle: between
// two writes the set-point moves with q̇_ref (exactly), stops at the joint limits, and the twin's
// teaching rows carry no host-rate acceleration bias (the held staircase gave q̈ ≈ −2.3 s⁻¹·q̇).
#include "offline/sim/admittance_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "offline/log/read_log.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/constants.hpp"

namespace {

using tpf::test::kArm4Joints;

using namespace tpf::offline;

constexpr double kHostPeriod = 0.0025;  // s

AdmittanceController pushed_controller(const TwinVector& upper) {
  TeachingConfig config;
  AdmittanceController c(config, TwinFriction{std::vector<JointFriction>(kArm4Joints)},
                         TwinVector::Zero(kArm4Joints), TwinVector::Constant(kArm4Joints, -3.0),
                         upper);
  const TwinVector tau = twin_vector({2.0, -1.0, 0.5, 0.0});  // N·m
  for (int k = 0; k < 40; ++k)
    c.follow(tau, /*max_pad_kpa=*/2.0, kHostPeriod);
  return c;
}

TEST(AdmittanceController, GoalMovesWithTheCommandedVelocityBetweenWrites) {
  const AdmittanceController c = pushed_controller(TwinVector::Constant(kArm4Joints, 3.0));
  ASSERT_GT(std::abs(c.dq_ref()[0]), 0.05) << "the push must move joint 1";
  TwinVector q, dq;
  for (const double s : {0.0, 0.0005, 0.0013, 0.0025}) {
    c.goal(s, q, dq);
    for (int j = 0; j < kArm4Joints; ++j) {
      EXPECT_NEAR(q[j], c.q_ref()[j] + c.dq_ref()[j] * s, 1e-15) << "s " << s << " joint " << j;
      EXPECT_EQ(dq[j], c.dq_ref()[j]);
    }
  }
  // A held reference would leave joint 1 a whole cycle of motion behind.
  c.goal(kHostPeriod, q, dq);
  EXPECT_NEAR(q[0] - c.q_ref()[0], c.dq_ref()[0] * kHostPeriod, 1e-15);
  EXPECT_GT(std::abs(q[0] - c.q_ref()[0]), 1e-4);
}

TEST(AdmittanceController, GoalStopsAtTheJointLimit) {
  const AdmittanceController free = pushed_controller(TwinVector::Constant(kArm4Joints, 3.0));
  // Joint 1 moves up; put its limit just beyond the last write.
  TwinVector upper = TwinVector::Constant(kArm4Joints, 3.0);
  upper[0] = free.q_ref()[0] + 0.5 * free.dq_ref()[0] * kHostPeriod;
  ASSERT_GT(free.dq_ref()[0], 0.0);
  const AdmittanceController c = pushed_controller(upper);
  ASSERT_DOUBLE_EQ(c.q_ref()[0], free.q_ref()[0]);
  TwinVector q, dq;
  c.goal(kHostPeriod, q, dq);
  EXPECT_DOUBLE_EQ(q[0], upper[0]);
  EXPECT_EQ(dq[0], 0.0);
  EXPECT_NEAR(q[1], c.q_ref()[1] + c.dq_ref()[1] * kHostPeriod, 1e-15);
  EXPECT_EQ(dq[1], c.dq_ref()[1]);
}

// Slope c of (q̈_sample − q̈_rows) against q̇ over a teaching log's moving rows of joint j, where
// q̈_sample = gt_ddq (the twin's last inner step before the row) and q̈_rows the central difference
// of the logged velocities: the part of the sampled acceleration the rows cannot show.
double sampled_acceleration_slope(const Log& log, int j) {
  const auto t = log.col("t");
  const auto dq = log.col(indexed_name("dq", j));
  const auto ddq = log.col(indexed_name("gt_ddq", j));
  double num = 0.0, den = 0.0;
  long rows = 0;
  for (Eigen::Index k = 1; k + 1 < log.rows(); ++k) {
    if (std::abs(dq(k)) < 0.05) continue;
    const double ddq_rows = (dq(k + 1) - dq(k - 1)) / (t(k + 1) - t(k - 1));
    num += (ddq(k) - ddq_rows) * dq(k);
    den += dq(k) * dq(k);
    ++rows;
  }
  EXPECT_GT(rows, 500) << "joint " << j << " must move in the teaching log";
  return num / den;
}

TEST(AdmittanceController, TeachingRowsCarryNoHostRateAccelerationBias) {
  const Scenario s = load_scenario(TPF_TEST_DATA_DIR "/scenarios/teaching.json");
  const Log log = simulate_to_log(s, 5, 12.0);
  // Held reference: −2.06 (joint 1) and −2.22 s⁻¹ (joint 2) here; first-order hold: −0.04, −0.01.
  for (int j = 1; j <= 2; ++j)
    EXPECT_NEAR(sampled_acceleration_slope(log, j), 0.0, 0.3) << "joint " << j;
}

}  // namespace
