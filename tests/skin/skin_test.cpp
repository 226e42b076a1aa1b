// The skin on the arm: pad geometry in the world frame, several pads, bad layouts, NaN pads.
#include "tpf/skin/skin.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "support/arm_fixture.hpp"
#include "support/constants.hpp"

namespace {

using tpf::test::arm;
using tpf::test::data_path;
constexpr int kPads = 11;
using tpf::test::kPeriod;
using ArmSkin = tpf::Skin<double, kPads>;

std::vector<tpf::Pad> pads() {
  return tpf::load_pads(data_path("arm4.pads.json"), arm());
}

TEST(Skin, PadPointAndNormalInTheWorldFrame) {
  const ArmSkin skin(pads(), {}, tpf::test::kJoints);
  tpf::test::ArmData data;
  tpf::test::RandomStates random(3);
  for (int trial = 0; trial < 20; ++trial) {
    const tpf::test::Vec q = random.vector(1.5);
    tpf::forward_kinematics(arm(), data, q);
    for (int k = 0; k < kPads; ++k) {
      const auto& g = skin.geometry(k);
      // Independent chain product of the joint placements and rotations.
      tpf::Transform<double> T;
      for (int i = 0; i < g.link; ++i) {
        tpf::Transform<double> joint = arm().joint_placements[i];
        joint.R = joint.R * Eigen::AngleAxisd(q[i], arm().axes[i]).toRotationMatrix();
        T = T * joint;
      }
      EXPECT_LT((tpf::pad_point_in_world(data, g) - T.apply(g.center)).norm(), 1e-12);
      const tpf::Vector3<double> n = tpf::pad_normal_in_world(data, g);
      EXPECT_LT((n - T.R * g.normal).norm(), 1e-12);
      EXPECT_NEAR(n.norm(), 1.0, 1e-12);
      // The contact frame's z axis is the outward normal.
      EXPECT_LT((tpf::contact_frame_in_world(data, g.link, g.normal).col(2) - n).norm(), 1e-12);
    }
  }
}

TEST(Skin, SeveralPadsAtOnceAndTheMostLoaded) {
  ArmSkin skin(pads(), {}, tpf::test::kJoints);
  ArmSkin::Pressures p = ArmSkin::Pressures::Zero();
  skin.reset(0.0, p);
  for (int k = 1; k <= 100; ++k) {
    p[2] = k > 10 ? 1.0 : 0.0;
    p[9] = k > 30 ? 3.0 : 0.0;
    skin.update(k * kPeriod, kPeriod, p);
    if (k == 11) {
      EXPECT_TRUE(skin.onset(2));  // a 1 kPa step crosses the on level at once
    }
  }
  EXPECT_TRUE(skin.in_contact(2));
  EXPECT_TRUE(skin.in_contact(9));
  EXPECT_FALSE(skin.in_contact(0));
  EXPECT_EQ(skin.most_loaded(), 9);
  EXPECT_NEAR(skin.normal_force(9), 3.0 * 1000.0 * skin.geometry(9).area, 1e-6);
  EXPECT_LT(skin.detector(2).onset_time(), skin.detector(9).onset_time());
  // Pad 9 released: pad 2 stays on.
  for (int k = 101; k <= 200; ++k) {
    p[9] = 0.0;
    skin.update(k * kPeriod, kPeriod, p);
  }
  EXPECT_FALSE(skin.in_contact(9));
  EXPECT_TRUE(skin.any_contact());
  EXPECT_EQ(skin.most_loaded(), 2);
}

TEST(Skin, NonFinitePressureKeepsThePadState) {
  ArmSkin skin(pads(), {}, tpf::test::kJoints);
  ArmSkin::Pressures p = ArmSkin::Pressures::Constant(2.0);
  skin.reset(0.0, ArmSkin::Pressures::Zero());
  for (int k = 1; k < 50; ++k)
    skin.update(k * kPeriod, kPeriod, p);
  const double before = skin.load_kpa(4);
  p[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(skin.update(50 * kPeriod, kPeriod, p), 1);
  EXPECT_TRUE(skin.in_contact(4));
  EXPECT_DOUBLE_EQ(skin.load_kpa(4), before);
}

TEST(Skin, RefusesALayoutOfTheWrongSize) {
  auto layout = pads();
  layout.pop_back();
  EXPECT_THROW(ArmSkin(layout, {}, tpf::test::kJoints), tpf::Error);
  layout = pads();
  layout[0].link = 7;
  EXPECT_THROW(ArmSkin(layout, {}, tpf::test::kJoints), tpf::Error);
}

}  // namespace
