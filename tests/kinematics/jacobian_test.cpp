#include <gtest/gtest.h>

#include "support/arm_fixture.hpp"

namespace tpf::test {
namespace {

/// Rotation vector θ·u of R (the inverse of Rodrigues' formula).
Vector3<double> rotation_vector(const Matrix3<double>& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

TEST(Jacobian, MatchesFiniteDifferenceKinematicsOnEveryLink) {
  ArmData data;
  RandomStates rs(11);
  const double h = 1e-6;
  for (int trial = 0; trial < 40; ++trial) {
    const Vec q = rs.vector(3.0);
    const int link = 1 + trial % kJoints;
    const Vector3<double> local = rs.point(0.2);
    forward_kinematics(arm(), data, q);
    const Vector3<double> p = data.oMi[link].apply(local);
    const Jacobian<double, kJoints> J = point_jacobian(arm(), data, link, p);
    for (int i = 0; i < kJoints; ++i) {
      ArmData plus, minus;
      forward_kinematics(arm(), plus, Vec(q + h * Vec::Unit(i)));
      forward_kinematics(arm(), minus, Vec(q - h * Vec::Unit(i)));
      const Vector3<double> v =
          (plus.oMi[link].apply(local) - minus.oMi[link].apply(local)) / (2 * h);
      const Vector3<double> w =
          rotation_vector(plus.oMi[link].R * minus.oMi[link].R.transpose()) / (2 * h);
      EXPECT_LT((J.col(i).head<3>() - v).norm(), 1e-8) << "link " << link << " joint " << i + 1;
      EXPECT_LT((J.col(i).tail<3>() - w).norm(), 1e-8) << "link " << link << " joint " << i + 1;
    }
  }
}

TEST(Jacobian, ContactFrameHasZAlongTheNormalAndIsARotation) {
  RandomStates rs(12);
  for (int trial = 0; trial < 20; ++trial) {
    const Vector3<double> n = rs.point(1.0).normalized();
    const Matrix3<double> R = contact_frame_in_link(n);
    EXPECT_LT((R.transpose() * R - Matrix3<double>::Identity()).norm(), 1e-14);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
    EXPECT_LT((R.col(2) - n).norm(), 1e-14);
  }
}

TEST(Jacobian, RotatedJacobianGivesContactFrameVelocities) {
  ArmData data;
  RandomStates rs(13);
  const Vec q = rs.vector(2.0), dq = rs.vector(1.0);
  forward_kinematics(arm(), data, q);
  const Pad pad = load_pads(data_path("arm4.pads.json"), arm()).front();
  const Vector3<double> p = data.oMi[pad.link].apply(pad.center);
  const Matrix3<double> Rc = contact_frame_in_world(data, pad.link, pad.normal);
  const Jacobian<double, kJoints> Jw = point_jacobian(arm(), data, pad.link, p);
  const Jacobian<double, kJoints> Jc = rotate_jacobian(Jw, Rc);
  EXPECT_LT((Jc * dq - (Vector6<double>() << Rc.transpose() * (Jw * dq).head<3>(),
                        Rc.transpose() * (Jw * dq).tail<3>())
                           .finished())
                .norm(),
            1e-14);
  // A push along the inward normal (−z of the contact frame) in world coordinates:
  const Vector3<double> push_world = -Rc.col(2);
  EXPECT_NEAR((Jc.topRows<3>().transpose() * Vector3<double>(0, 0, -1) -
               Jw.topRows<3>().transpose() * push_world)
                  .norm(),
              0.0, 1e-14);
}

TEST(Kinematics, ArmAtZeroMatchesThePublishedJointOrigins) {
  ArmData data;
  forward_kinematics(arm(), data, Vec::Zero());
  // hardware.md §6: joint origins accumulate at q = 0 (all rpy = 0).
  EXPECT_LT((data.oMi[1].p - Vector3<double>(0, 0, 0.126)).norm(), 1e-15);
  EXPECT_LT((data.oMi[2].p - Vector3<double>(0, 0.069, 0.159)).norm(), 1e-15);
  EXPECT_LT((data.oMi[3].p - Vector3<double>(0.030, 0.0575, 0.423)).norm(), 1e-15);
  EXPECT_LT((data.oMi[4].p - Vector3<double>(0.225, 0.0, 0.453)).norm(), 1e-15);
}

}  // namespace
}  // namespace tpf::test
