// The PH54 drive model: gains from bandwidths, current limit, anti-windup, disabled drive.
#include "offline/sim/ph54_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include "support/constants.hpp"

namespace {

using tpf::test::kArm4Joints;

using tpf::offline::DriveConfig;
using tpf::offline::Ph54Drive;
using tpf::offline::twin_vector;
using tpf::offline::TwinVector;

TEST(Ph54Drive, GainsFollowBandwidthsAndInertia) {
  DriveConfig c;
  c.position_bandwidth_hz = 2.0;
  c.velocity_bandwidth_hz = 10.0;
  c.integral_corner_hz = 1.0;
  const TwinVector J = twin_vector({2.0, 1.0, 0.5, 0.25}), kt = twin_vector({4.8, 4.8, 4.6, 4.6});
  Ph54Drive d(c, J, kt, TwinVector::Constant(kArm4Joints, 5.0),
              TwinVector::Constant(kArm4Joints, 3.0));
  const double w = 2 * std::numbers::pi;
  EXPECT_NEAR(d.position_gain()[0], 2 * w, 1e-12);
  EXPECT_NEAR(d.velocity_gain()[2], 10 * w * 0.5 / 4.6, 1e-12);
  EXPECT_NEAR(d.integral_gain()[3], 1 * w * 10 * w * 0.25 / 4.6, 1e-12);
}

TEST(Ph54Drive, CurrentIsLimitedAndIntegratorDoesNotWindUp) {
  DriveConfig c;
  c.current_time_constant = 0.0;
  Ph54Drive d(c, TwinVector::Ones(kArm4Joints), TwinVector::Ones(kArm4Joints),
              TwinVector::Constant(kArm4Joints, 2.0), TwinVector::Constant(kArm4Joints, 3.0));
  d.reset(TwinVector::Zero(kArm4Joints));
  const TwinVector zero = TwinVector::Zero(kArm4Joints);
  // Blocked joint far from the reference: the current saturates at the limit...
  for (int k = 0; k < 20000; ++k)
    d.update(TwinVector::Constant(kArm4Joints, 1.0), zero, zero, zero, 5e-4);
  EXPECT_NEAR(d.current().maxCoeff(), 2.0, 1e-12);
  // ...and reverses within a few cycles once the error reverses (no wound-up integral).
  int cycles = 0;
  while (d.current()[0] > 0 && cycles < 1000) {
    d.update(TwinVector::Constant(kArm4Joints, -1.0), zero, zero, zero, 5e-4);
    ++cycles;
  }
  EXPECT_LT(cycles, 50);
}

TEST(Ph54Drive, HoldsAResetCurrentAtZeroErrorAndDisabledGivesZero) {
  DriveConfig c;
  Ph54Drive d(c, TwinVector::Ones(kArm4Joints), TwinVector::Ones(kArm4Joints),
              TwinVector::Constant(kArm4Joints, 5.0), TwinVector::Constant(kArm4Joints, 3.0));
  const TwinVector hold = twin_vector({0.5, -1.0, 0.2, 0.0}), zero = TwinVector::Zero(kArm4Joints);
  d.reset(hold);
  for (int k = 0; k < 100; ++k)
    d.update(zero, zero, zero, zero, 5e-4);
  EXPECT_TRUE(d.current().isApprox(hold, 1e-12));
  c.enabled = false;
  Ph54Drive off(c, TwinVector::Ones(kArm4Joints), TwinVector::Ones(kArm4Joints),
                TwinVector::Constant(kArm4Joints, 5.0), TwinVector::Constant(kArm4Joints, 3.0));
  off.reset(hold);
  EXPECT_TRUE(off.update(TwinVector::Ones(kArm4Joints), zero, zero, zero, 5e-4).isZero(0.0));
}

}  // namespace
