// Reference schedules: minimum-jerk identities, excitation coverage, contact script profile.
#include <gtest/gtest.h>

#include <cmath>

#include "offline/sim/contact_script.hpp"
#include "offline/sim/excitation_schedule.hpp"
#include "offline/sim/random.hpp"
#include "offline/sim/sensor_quantisation.hpp"
#include "support/constants.hpp"

namespace {

using tpf::test::kArm4Joints;

using namespace tpf::offline;

TEST(MinJerkSchedule, EndpointsPeakSpeedAndDerivative) {
  MinJerkSchedule s(TwinVector::Zero(kArm4Joints));
  for (int j = 0; j < kArm4Joints; ++j) {
    s.append(j, 0.0, 1.0);
    s.append(j, 0.5 * (j + 1), 2.0);
  }
  TwinVector q, dq, qa, dqa, qb, dqb;
  s.evaluate(0.5, q, dq);
  EXPECT_TRUE(q.isZero(0.0));
  s.evaluate(2.0, q, dq);  // middle of the move: half way, peak speed 1.875·Δ/T
  for (int j = 0; j < kArm4Joints; ++j) {
    EXPECT_NEAR(q[j], 0.25 * (j + 1), 1e-12);
    EXPECT_NEAR(dq[j], 1.875 * 0.5 * (j + 1) / 2.0, 1e-12);
  }
  // dq is the derivative of q (central difference).
  MinJerkSchedule a = s, b = s;
  a.evaluate(2.3 - 1e-6, qa, dqa);
  b.evaluate(2.3 + 1e-6, qb, dqb);
  s.evaluate(2.3, q, dq);
  EXPECT_TRUE(((qb - qa) / 2e-6).isApprox(dq, 1e-7));
  s.evaluate(10.0, q, dq);
  EXPECT_NEAR(q[3], 2.0, 1e-15);
  EXPECT_EQ(dq[3], 0.0);
}

TEST(ExcitationSchedule, StaysInRangeAndStartsMotionInBothDirections) {
  ExcitationConfig c;
  c.lower = twin_vector({-2.5, -1.2, -1.6, -2.0});
  c.upper = twin_vector({2.5, 1.2, 1.2, 2.0});
  Random rng(3);
  const TwinVector lower = c.lower, upper = c.upper;
  MinJerkSchedule s =
      make_excitation_schedule(c, TwinVector::Zero(kArm4Joints), lower, upper, 120.0, rng);
  TwinVector q, dq;
  int onsets_pos[kArm4Joints] = {}, onsets_neg[kArm4Joints] = {};
  TwinVector previous = TwinVector::Zero(kArm4Joints);
  for (int k = 0; k < 120 * 400; ++k) {
    s.evaluate(k / 400.0, q, dq);
    for (int j = 0; j < kArm4Joints; ++j) {
      EXPECT_GE(q[j], lower[j] - 1e-12);
      EXPECT_LE(q[j], upper[j] + 1e-12);
      if (previous[j] == 0.0 && dq[j] > 0) ++onsets_pos[j];
      if (previous[j] == 0.0 && dq[j] < 0) ++onsets_neg[j];
    }
    previous = dq;
  }
  for (int j = 0; j < kArm4Joints; ++j) {
    EXPECT_GE(onsets_pos[j], 5) << "joint " << j;
    EXPECT_GE(onsets_neg[j], 5) << "joint " << j;
  }
}

TEST(ContactScript, ProfileRampsHoldsAndReleases) {
  ContactScript script;
  ContactEvent e;
  e.pad = 2;
  e.t_on = 1.0;
  e.t_full = 1.5;
  e.t_release = 3.0;
  e.t_off = 3.5;
  e.normal_n = 10.0;
  e.shear_x_n = 2.0;
  script.add(e);
  EXPECT_EQ(script.at(0.5).pad, -1);
  EXPECT_NEAR(script.at(1.25).force_contact.z(), -5.0, 1e-12);  // min-jerk ramp is 1/2 mid-way
  const auto hold = script.at(2.0);
  EXPECT_EQ(hold.pad, 2);
  EXPECT_TRUE(hold.force_contact.isApprox(Eigen::Vector3d(2.0, 0.0, -10.0)));
  EXPECT_NEAR(script.at(3.25).force_contact.z(), -5.0, 1e-12);
  EXPECT_EQ(script.at(3.6).pad, -1);
}

TEST(Random, SameSeedSameSequenceAndSaneMoments) {
  Random a(42), b(42);
  double sum = 0, sum2 = 0;
  for (int k = 0; k < 100000; ++k) {
    const double x = a.normal();
    EXPECT_EQ(x, b.normal());
    sum += x;
    sum2 += x * x;
  }
  EXPECT_NEAR(sum / 1e5, 0.0, 0.02);
  EXPECT_NEAR(sum2 / 1e5, 1.0, 0.02);
  // Reference values pin the sequence across platforms (mt19937_64 is fully specified).
  Random c(1);
  EXPECT_DOUBLE_EQ(c.uniform(), static_cast<double>(std::mt19937_64(1)() >> 11) * 0x1.0p-53);
}

TEST(SensorQuantisation, Ph54Resolution) {
  EXPECT_NEAR(kPositionStep, 6.2590e-6, 1e-9);
  EXPECT_NEAR(quantise_position(1e-6), 0.0, 0.0);
  EXPECT_NEAR(quantise_position(4e-6), kPositionStep, 1e-18);
  EXPECT_NEAR(quantise_velocity(0.0011), 2 * std::acos(-1.0) / 6000.0, 1e-15);
  EXPECT_EQ(quantise_current_ma(12.6), 13.0);
}

}  // namespace
