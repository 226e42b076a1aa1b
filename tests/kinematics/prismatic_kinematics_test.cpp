// Forward kinematics and point Jacobians of chains with prismatic joints, against finite
// differences of the link poses, at Eigen::Dynamic and a fixed joint count.
#include <gtest/gtest.h>

#include <random>

#include "support/arm_fixture.hpp"
#include "support/random_arm.hpp"

namespace tpf::test {
namespace {

/// A random 5-joint arm whose joints 2 and 5 are prismatic.
Model<double, Eigen::Dynamic> sliding_arm() {
  Model<double, Eigen::Dynamic> model = random_arm(5, 77);
  model.joint_types[1] = model.joint_types[4] = JointType::prismatic;
  model.update_constants();
  return model;
}

Vector3<double> rotation_vector_of(const Matrix3<double>& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

template <int N>
void expect_jacobian_matches_finite_differences(const Model<double, N>& model) {
  Data<double, N> data(model);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  const int n = model.joint_count();
  const double h = 1e-6;
  for (int trial = 0; trial < 30; ++trial) {
    JointVector<double, N> q(n);
    for (int j = 0; j < n; ++j)
      q(j) = u(rng);
    const int link = 1 + trial % n;
    const Vector3<double> local(0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng));
    forward_kinematics(model, data, q);
    const Vector3<double> p = data.oMi[link].apply(local);
    const Jacobian<double, N> J = point_jacobian(model, data, link, p);
    for (int i = 0; i < n; ++i) {
      Data<double, N> plus(model), minus(model);
      JointVector<double, N> e = JointVector<double, N>::Zero(n);
      e(i) = h;
      forward_kinematics(model, plus, JointVector<double, N>(q + e));
      forward_kinematics(model, minus, JointVector<double, N>(q - e));
      const Vector3<double> v =
          (plus.oMi[link].apply(local) - minus.oMi[link].apply(local)) / (2 * h);
      const Vector3<double> w =
          rotation_vector_of(plus.oMi[link].R * minus.oMi[link].R.transpose()) / (2 * h);
      EXPECT_LT((J.col(i).template head<3>() - v).norm(), 1e-8)
          << "link " << link << " joint " << i + 1;
      EXPECT_LT((J.col(i).template tail<3>() - w).norm(), 1e-8)
          << "link " << link << " joint " << i + 1;
    }
  }
}

TEST(PrismaticKinematics, JacobianMatchesFiniteDifferencesAtDynamicAndFixedCount) {
  const Model<double, Eigen::Dynamic> model = sliding_arm();
  expect_jacobian_matches_finite_differences(model);
  expect_jacobian_matches_finite_differences(joint_count_cast<5>(model));
}

TEST(PrismaticKinematics, APrismaticJointMovesItsLinkAlongTheWorldAxisWithoutTurningIt) {
  const Model<double, Eigen::Dynamic> model = sliding_arm();
  Data<double, Eigen::Dynamic> a(model), b(model);
  Eigen::VectorXd q(5);
  q << 0.3, 0.1, -0.7, 1.2, 0.05;
  forward_kinematics(model, a, q);
  q(1) += 0.25;  // 25 cm further along joint 2's axis
  forward_kinematics(model, b, q);
  EXPECT_LT((b.oMi[2].p - a.oMi[2].p - 0.25 * a.axis_world[2]).norm(), 1e-14);
  EXPECT_LT((b.oMi[2].R - a.oMi[2].R).norm(), 1e-15);
  // At q = 0 the link frame is the joint frame.
  forward_kinematics(model, a, Eigen::VectorXd::Zero(5));
  EXPECT_LT((a.liMi[2].p - model.joint_placements[1].p).norm(), 1e-15);
  EXPECT_EQ(a.liMi[2].R, model.joint_placements[1].R);
}

}  // namespace
}  // namespace tpf::test
