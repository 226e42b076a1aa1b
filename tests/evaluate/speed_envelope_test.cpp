// The compensator's domain read off a calibration log: the per-joint speed envelope.
#include <gtest/gtest.h>

#include <limits>

#include "offline/replay/replay_estimator.hpp"

namespace {

using namespace tpf::offline;

TEST(SpeedEnvelope, PerJointMaximumOfTheAbsoluteSpeedSkippingNonFiniteRows) {
  std::vector<ReplaySample> samples(3);
  for (ReplaySample& s : samples)
    s.resize(4, 0);
  samples[0].t = 0.0;
  samples[0].dq << 0.1, -0.7, 0.0, 0.2;
  samples[1].t = 0.0025;
  samples[1].dq << -0.4, 0.3, 0.0, -0.25;
  samples[2].t = 0.005;  // a bad row: its 9 rad/s must not widen the domain
  samples[2].dq << 9.0, std::numeric_limits<double>::quiet_NaN(), 9.0, 9.0;
  const auto v = speed_envelope(samples);
  ASSERT_EQ(v.size(), 4);
  EXPECT_DOUBLE_EQ(v[0], 0.4);
  EXPECT_DOUBLE_EQ(v[1], 0.7);
  EXPECT_DOUBLE_EQ(v[2], 0.0);
  EXPECT_DOUBLE_EQ(v[3], 0.25);
}

TEST(SpeedEnvelope, OfNineJointsAndOfNoSample) {
  std::vector<ReplaySample> samples(2);
  for (ReplaySample& s : samples)
    s.resize(9, 0);
  samples[0].dq[8] = -1.5;
  samples[1].dq[3] = 0.5;
  const auto v = speed_envelope(samples);
  ASSERT_EQ(v.size(), 9);
  EXPECT_DOUBLE_EQ(v[8], 1.5);
  EXPECT_DOUBLE_EQ(v[3], 0.5);
  EXPECT_DOUBLE_EQ(v[0], 0.0);
  EXPECT_EQ(speed_envelope({}).size(), 0);
}

}  // namespace
