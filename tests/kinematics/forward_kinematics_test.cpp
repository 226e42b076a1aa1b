// forward_kinematics' shortcuts give the numbers of the plain recursion: a world axis taken as a
// column of the link's rotation (coordinate axes), and the poses of a prefix of the chain.
#include "tpf/kinematics/forward_kinematics.hpp"

#include <gtest/gtest.h>

#include <random>

namespace tpf {
namespace {

constexpr int kChain = 7;

/// A chain whose joints turn about +x, −x, +y, −y, +z, −z and one oblique axis, each placed with a
/// random rotation and offset.
Model<double, kChain> chain_of_every_axis() {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vector3<double> oblique = Vector3<double>(0.3, -0.5, 0.8).normalized();
  const std::array<Vector3<double>, kChain> axes{Vector3<double>::UnitX(),
                                                 -Vector3<double>::UnitX(),
                                                 Vector3<double>::UnitY(),
                                                 -Vector3<double>::UnitY(),
                                                 Vector3<double>::UnitZ(),
                                                 -Vector3<double>::UnitZ(),
                                                 oblique};
  Model<double, kChain> m;
  for (int k = 0; k < kChain; ++k) {
    m.axes[k] = axes[k];
    m.joint_placements[k].R =
        Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
    m.joint_placements[k].p = Vector3<double>(u(rng), u(rng), u(rng));
  }
  m.update_constants();
  return m;
}

TEST(ForwardKinematics, CoordinateAxesAreRecognisedWithTheirSign) {
  const auto m = chain_of_every_axis();
  const std::array<int, kChain> expected{1, -1, 2, -2, 3, -3, 0};
  for (int k = 0; k < kChain; ++k)
    EXPECT_EQ(m.constants.axis_coordinate[k], expected[k]) << "joint " << k + 1;
}

TEST(ForwardKinematics, WorldAxesEqualTheRotationTimesTheAxis) {
  const auto m = chain_of_every_axis();
  Data<double, kChain> data;
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int trial = 0; trial < 50; ++trial) {
    JointVector<double, kChain> q;
    for (int j = 0; j < kChain; ++j)
      q[j] = u(rng);
    forward_kinematics(m, data, q);
    for (int k = 1; k <= kChain; ++k) {
      const Vector3<double> product = data.oMi[k].R * m.axes[k - 1];
      for (int i = 0; i < 3; ++i)  // exactly: the product's other terms are zeros
        EXPECT_EQ(data.axis_world[k][i], product[i]) << "link " << k << " row " << i;
    }
  }
}

TEST(ForwardKinematics, APrefixOfTheChainHasTheFullChainsPosesAndLeavesTheRest) {
  const auto m = chain_of_every_axis();
  JointVector<double, kChain> q;
  q << 0.3, -1.2, 2.0, 0.7, -0.4, 1.5, -2.2;
  Data<double, kChain> full;
  forward_kinematics(m, full, q);
  for (int last = 0; last <= kChain; ++last) {
    Data<double, kChain> part;
    const Transform<double> marker{Matrix3<double>::Constant(7.0), Vector3<double>::Constant(7.0)};
    part.oMi.fill(marker);
    forward_kinematics(m, part, q, last);
    for (int k = 1; k <= kChain; ++k) {
      if (k <= last) {
        EXPECT_EQ(part.oMi[k].R, full.oMi[k].R) << "last " << last << " link " << k;
        EXPECT_EQ(part.oMi[k].p, full.oMi[k].p) << "last " << last << " link " << k;
        EXPECT_EQ(part.axis_world[k], full.axis_world[k]) << "last " << last << " link " << k;
      } else {
        EXPECT_EQ(part.oMi[k].R, marker.R) << "last " << last << " link " << k << " was written";
      }
    }
  }
}

}  // namespace
}  // namespace tpf
