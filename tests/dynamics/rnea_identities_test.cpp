#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "support/arm_fixture.hpp"

namespace tpf::test {
namespace {

TEST(Rnea, RegressorTimesParametersEqualsRneaPlusFriction) {
  ArmData data;
  RandomStates rs(1);
  const Vec coulomb = rs.vector(1.0).cwiseAbs(), viscous = rs.vector(2.0).cwiseAbs();
  const auto pi = dynamic_parameters(arm(), coulomb, viscous);
  Regressor<double, kJoints> Y;
  for (int trial = 0; trial < 50; ++trial) {
    const Vec q = rs.vector(3.0), dq = rs.vector(2.0), ddq = rs.vector(5.0);
    compute_regressor(arm(), data, q, dq, ddq, Y);
    Vec expected = rnea(arm(), data, q, dq, ddq);
    for (int j = 0; j < kJoints; ++j)
      expected(j) += coulomb(j) * (dq(j) > 0 ? 1 : -1) + viscous(j) * dq(j);
    EXPECT_LT((Y * pi - expected).norm(), 1e-10 * (1 + expected.norm()));
  }
}

TEST(Rnea, MassMatrixIsSymmetricPositiveDefiniteAndEqualsRneaColumns) {
  ArmData data;
  RandomStates rs(2);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec q = rs.vector(3.0);
    const JointMatrix<double, kJoints> M = compute_mass_matrix(arm(), data, q);
    EXPECT_LT((M - M.transpose()).norm(), 1e-14);
    for (int k = 1; k <= kJoints; ++k)  // the composite inertias are built symmetric, exactly
      EXPECT_TRUE(data.composite_inertia[k] == data.composite_inertia[k].transpose()) << k;
    const double smallest =
        Eigen::SelfAdjointEigenSolver<JointMatrix<double, kJoints>>(M).eigenvalues().minCoeff();
    EXPECT_GT(smallest, 0.0);
    const Vec g = compute_gravity(arm(), data, q);
    for (int i = 0; i < kJoints; ++i) {
      const Vec column = rnea(arm(), data, q, Vec::Zero(), Vec::Unit(i)) - g;
      EXPECT_LT((column - M.col(i)).norm(), 1e-12) << "column " << i;
    }
  }
}

TEST(Rnea, ArmatureAddsToTheDiagonalOnly) {
  ArmData data, bare_data;
  Arm bare = arm();
  bare.armature.setZero();
  const Vec q = RandomStates(3).vector(2.0);
  const JointMatrix<double, kJoints> difference =
      compute_mass_matrix(arm(), data, q) - compute_mass_matrix(bare, bare_data, q);
  EXPECT_LT((difference - JointMatrix<double, kJoints>(arm().armature.asDiagonal())).norm(), 1e-14);
  EXPECT_GT(arm().armature(0), 0.5);  // 500:1 gearing: the rotor dominates the inertia
}

TEST(Rnea, CoriolisMatrixSatisfiesCPlusCTransposeEqualsMdot) {
  ArmData data;
  RandomStates rs(4);
  const double h = 1e-6;
  for (int trial = 0; trial < 30; ++trial) {
    const Vec q = rs.vector(3.0), dq = rs.vector(2.0);
    const JointMatrix<double, kJoints> C = compute_coriolis_matrix(arm(), data, q, dq);
    const JointMatrix<double, kJoints> Mp = compute_mass_matrix(arm(), data, Vec(q + h * dq));
    const JointMatrix<double, kJoints> Mm = compute_mass_matrix(arm(), data, Vec(q - h * dq));
    const JointMatrix<double, kJoints> Mdot = (Mp - Mm) / (2 * h);
    EXPECT_LT((C + C.transpose() - Mdot).norm(), 1e-7 * (1 + Mdot.norm()));
    const Vec c = velocity_torques(arm(), data, q, dq);
    EXPECT_LT((C * dq - c).norm(), 1e-12 * (1 + c.norm()));
    EXPECT_LT((coriolis_transpose_times_velocity(arm(), data, q, dq) - C.transpose() * dq).norm(),
              1e-14);
  }
}

TEST(Rnea, GravityIsTheGradientOfPotentialEnergy) {
  ArmData data;
  RandomStates rs(5);
  const double h = 1e-6;
  for (int trial = 0; trial < 30; ++trial) {
    const Vec q = rs.vector(3.0);
    const Vec g = compute_gravity(arm(), data, q);
    for (int i = 0; i < kJoints; ++i) {
      const double dV = (potential_energy(arm(), data, Vec(q + h * Vec::Unit(i))) -
                         potential_energy(arm(), data, Vec(q - h * Vec::Unit(i)))) /
                        (2 * h);
      EXPECT_NEAR(g(i), dV, 1e-7) << "joint " << i + 1;
    }
  }
}

TEST(Rnea, ExternalForceEqualsSubtractingJacobianTranspose) {
  ArmData data;
  RandomStates rs(6);
  for (int trial = 0; trial < 30; ++trial) {
    const Vec q = rs.vector(3.0), dq = rs.vector(2.0), ddq = rs.vector(5.0);
    const int link = 1 + trial % kJoints;
    forward_kinematics(arm(), data, q);
    const Vector3<double> p = data.oMi[link].apply(rs.point(0.2));
    Vector6<double> w;
    w << rs.point(20.0), rs.point(2.0);
    const Jacobian<double, kJoints> J = point_jacobian(arm(), data, link, p);
    const Vec free = rnea(arm(), data, q, dq, ddq);
    const Vec pushed = rnea(arm(), data, q, dq, ddq, link, p, w);
    EXPECT_LT((pushed - (free - J.transpose() * w)).norm(), 1e-11);
  }
}

TEST(Rnea, ForwardDynamicsInvertsInverseDynamics) {
  ArmData data;
  RandomStates rs(7);
  for (int trial = 0; trial < 30; ++trial) {
    const Vec q = rs.vector(3.0), dq = rs.vector(2.0), ddq = rs.vector(5.0);
    const Vec tau = rnea(arm(), data, q, dq, ddq);
    EXPECT_LT((forward_dynamics(arm(), data, q, dq, tau) - ddq).norm(), 1e-10);
  }
}

TEST(Rnea, StaticGravityMatchesHandComputationForJoint2) {
  // Arm stretched up (q = 0): gravity is parallel to the upper arm, so joint 2 only feels the
  // horizontal offsets of the centres of mass. Compare with Σ m_k g x_k about joint 2's y axis.
  ArmData data;
  const Vec q = Vec::Zero();
  const Vec g = compute_gravity(arm(), data, q);
  forward_kinematics(arm(), data, q);
  double expected = 0;
  for (int k = 2; k <= kJoints; ++k) {
    const Vector3<double> c = data.oMi[k].apply(arm().inertias[k].com) - data.oMi[2].p;
    expected -= arm().inertias[k].mass * 9.81 *
                c.x();  // gravity pulls with (c × m g)_y = m g c_x; G holds it
  }
  EXPECT_NEAR(g(1), expected, 1e-12);
  EXPECT_NEAR(g(0), 0.0, 1e-12);  // a vertical axis carries no gravity torque
}

}  // namespace
}  // namespace tpf::test
