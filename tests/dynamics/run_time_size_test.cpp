// The core at a run-time joint count (Eigen::Dynamic): one compiled copy of kinematics, dynamics,
// regressor and friction for any arm. Checked against the same algorithms at a fixed count on the
// project's robot files (4 and 7 joints), against the textbook reference (reference_dynamics.hpp)
// on a random 9-joint arm, and by the dynamics identities that need no reference.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <random>

#include "dynamics/reference_dynamics.hpp"
#include "support/arm_fixture.hpp"
#include "support/random_arm.hpp"
#include "tpf/friction/lugre.hpp"

namespace tpf::test {
namespace {

using DynModel = Model<double, Eigen::Dynamic>;
using DynData = Data<double, Eigen::Dynamic>;
using DynVec = Eigen::VectorXd;

DynVec random_dynamic(std::mt19937_64& rng, int n, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  DynVec v(n);
  for (int j = 0; j < n; ++j)
    v(j) = u(rng);
  return v;
}

/// Every algorithm of the core at Eigen::Dynamic gives the numbers of the same algorithm at the
/// fixed count N (the same operations in the same order: equal to rounding).
template <int N>
void expect_dynamic_equals_fixed(const std::string& robot_file) {
  const Model<double, N> fixed = load_robot<double, N>(data_path(robot_file));
  const DynModel dynamic = load_robot<double, Eigen::Dynamic>(data_path(robot_file));
  ASSERT_EQ(dynamic.joint_count(), N);
  Data<double, N> fd(fixed);
  DynData dd(dynamic);
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    const JointVector<double, N> q = random_vector<N>(rng, 2.5), dq = random_vector<N>(rng, 2.0),
                                 ddq = random_vector<N>(rng, 4.0);
    const DynVec qd = q, dqd = dq, ddqd = ddq;
    const double tol = 1e-12;
    EXPECT_LT((rnea(fixed, fd, q, dq, ddq) - rnea(dynamic, dd, qd, dqd, ddqd)).norm(), tol);
    EXPECT_LT((compute_gravity(fixed, fd, q) - compute_gravity(dynamic, dd, qd)).norm(), tol);
    EXPECT_LT((compute_mass_matrix(fixed, fd, q) - compute_mass_matrix(dynamic, dd, qd)).norm(),
              tol);
    EXPECT_LT(
        (compute_coriolis_matrix(fixed, fd, q, dq) - compute_coriolis_matrix(dynamic, dd, qd, dqd))
            .norm(),
        tol);
    EXPECT_LT(
        (forward_dynamics(fixed, fd, q, dq, ddq) - forward_dynamics(dynamic, dd, qd, dqd, ddqd))
            .norm(),
        1e-9);
    forward_kinematics(fixed, fd, q);
    forward_kinematics(dynamic, dd, qd);
    const Vector3<double> point(0.02, -0.01, 0.05);
    for (int link = 1; link <= N; ++link) {
      EXPECT_LT((fd.oMi[link].p - dd.oMi[link].p).norm(), tol);
      const Vector3<double> p = fd.oMi[link].apply(point);
      EXPECT_LT((point_jacobian(fixed, fd, link, p) - point_jacobian(dynamic, dd, link, p)).norm(),
                tol);
    }
    Regressor<double, N> Yf;
    Eigen::MatrixXd Yd;
    compute_regressor(fixed, fd, q, dq, ddq, Yf);
    compute_regressor(dynamic, dd, qd, dqd, ddqd, Yd);
    ASSERT_EQ(Yd.rows(), N);
    ASSERT_EQ(Yd.cols(), 13 * N);
    EXPECT_LT((Yf - Yd).norm(), tol);
  }
}

TEST(RunTimeSize, FourJointArmEqualsTheFixedSizeAlgorithms) {
  expect_dynamic_equals_fixed<4>("arm4.robot.json");
}

TEST(RunTimeSize, KinovaGen3EqualsTheFixedSizeAlgorithms) {
  expect_dynamic_equals_fixed<7>("real/kinova-gen3/gen3.robot.json");
}

TEST(RunTimeSize, NineJointArmAgreesWithTheTextbookReference) {
  const DynModel model = random_arm(9, 5);
  const Model<double, 9> fixed = joint_count_cast<9>(model);
  DynData data(model);
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const DynVec q = random_dynamic(rng, 9, 3.0), dq = random_dynamic(rng, 9, 2.0),
                 ddq = random_dynamic(rng, 9, 5.0);
    const JointVector<double, 9> qf = q, dqf = dq, ddqf = ddq;
    const Eigen::VectorXd tau = reference::rnea(fixed, qf, dqf, ddqf);
    EXPECT_LT((rnea(model, data, q, dq, ddq) - tau).norm(), 1e-10 * (1 + tau.norm()));
    const Eigen::MatrixXd M = reference::mass_matrix(fixed, qf);
    EXPECT_LT((compute_mass_matrix(model, data, q) - M).norm(), 1e-10 * (1 + M.norm()));
    Eigen::MatrixXd Y;
    compute_regressor(model, data, q, dq, ddq, Y);
    EXPECT_LT((Y - reference::regressor(fixed, qf, dqf, ddqf)).norm(), 1e-9 * (1 + Y.norm()));
  }
}

TEST(RunTimeSize, NineJointArmKeepsTheDynamicsIdentities) {
  const DynModel model = random_arm(9, 9);
  DynData data(model);
  std::mt19937_64 rng(3);
  const int n = 9;
  for (int trial = 0; trial < 10; ++trial) {
    const DynVec q = random_dynamic(rng, n, 3.0), dq = random_dynamic(rng, n, 2.0),
                 ddq = random_dynamic(rng, n, 5.0);
    // Y π = RNEA + τ_c sgn(q̇) + b q̇.
    const DynVec coulomb = random_dynamic(rng, n, 1.0).cwiseAbs(),
                 viscous = random_dynamic(rng, n, 1.0).cwiseAbs();
    Eigen::MatrixXd Y;
    compute_regressor(model, data, q, dq, ddq, Y);
    DynVec expected = rnea(model, data, q, dq, ddq);
    expected += coulomb.cwiseProduct(dq.cwiseSign()) + viscous.cwiseProduct(dq);
    EXPECT_LT((Y * dynamic_parameters(model, coulomb, viscous) - expected).norm(),
              1e-10 * (1 + expected.norm()));
    // M symmetric positive definite; forward dynamics inverts the inverse dynamics.
    const Eigen::MatrixXd M = compute_mass_matrix(model, data, q);
    EXPECT_LT((M - M.transpose()).norm(), 1e-12);
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().minCoeff(), 0.0);
    const DynVec tau = rnea(model, data, q, dq, ddq);
    EXPECT_LT((forward_dynamics(model, data, q, dq, tau) - ddq).norm(), 1e-8 * (1 + ddq.norm()));
    // C + Cᵀ = Ṁ, Ṁ by central differences along q̇.
    const double h = 1e-6;
    const Eigen::MatrixXd C = compute_coriolis_matrix(model, data, q, dq);
    const Eigen::MatrixXd M_plus = compute_mass_matrix(model, data, DynVec(q + h * dq));
    const Eigen::MatrixXd M_minus = compute_mass_matrix(model, data, DynVec(q - h * dq));
    const Eigen::MatrixXd M_dot = (M_plus - M_minus) / (2 * h);
    EXPECT_LT((C + C.transpose() - M_dot).norm(), 1e-6 * (1 + M_dot.norm()));
    // The point Jacobian against finite differences of forward kinematics.
    forward_kinematics(model, data, q);
    const Vector3<double> local(0.03, 0.01, -0.02);
    const Vector3<double> p = data.oMi[n].apply(local);
    const Eigen::MatrixXd J = point_jacobian(model, data, n, p);
    for (int i = 0; i < n; ++i) {
      DynData plus(model), minus(model);
      forward_kinematics(model, plus, DynVec(q + h * DynVec::Unit(n, i)));
      forward_kinematics(model, minus, DynVec(q - h * DynVec::Unit(n, i)));
      const Vector3<double> v = (plus.oMi[n].apply(local) - minus.oMi[n].apply(local)) / (2 * h);
      EXPECT_LT((J.col(i).head<3>() - v).norm(), 1e-7) << "column " << i;
    }
  }
}

TEST(RunTimeSize, FrictionAtRunTimeSizeEqualsTheFixedSize) {
  StribeckParameters<double, 4> fixed;
  StribeckParameters<double, Eigen::Dynamic> dynamic;
  dynamic.resize(4);
  EXPECT_EQ(dynamic.stribeck_velocity, Eigen::VectorXd::Ones(4));
  EXPECT_EQ(dynamic.stribeck_exponent, Eigen::VectorXd::Constant(4, 2.0));
  fixed.coulomb << 0.3, 0.2, 0.1, 0.05;
  fixed.static_friction << 0.5, 0.3, 0.2, 0.1;
  fixed.viscous << 0.4, 0.3, 0.2, 0.1;
  fixed.load_coulomb << 0.01, 0.02, 0.0, 0.03;
  fixed.neighbour_load_coulomb(0, 1) = 0.02;
  dynamic.coulomb = fixed.coulomb;
  dynamic.static_friction = fixed.static_friction;
  dynamic.viscous = fixed.viscous;
  dynamic.load_coulomb = fixed.load_coulomb;
  dynamic.neighbour_load_coulomb = fixed.neighbour_load_coulomb;
  const Vec dq(0.3, -0.02, 0.0, 1.5), abs_g(2.0, 5.0, 1.0, 0.2);
  const DynVec dqd = dq, gd = abs_g;
  EXPECT_LT((stribeck_friction(fixed, dq, abs_g) - stribeck_friction(dynamic, dqd, gd)).norm(),
            1e-15);
  EXPECT_LT((stribeck_friction(fixed, dq) - stribeck_friction(dynamic, dqd)).norm(), 1e-15);
  LuGreParameters<double, Eigen::Dynamic> lugre;
  lugre.resize(4);
  lugre.stribeck = dynamic;
  LuGreState<double, Eigen::Dynamic> state{DynVec::Zero(4)};
  const DynVec tau = lugre_step(lugre, state, dqd, gd, 0.0025);
  ASSERT_EQ(tau.size(), 4);
  LuGreParameters<double, 4> lugre_fixed;
  lugre_fixed.stribeck = fixed;
  LuGreState<double, 4> state_fixed;
  EXPECT_LT((lugre_step(lugre_fixed, state_fixed, dq, abs_g, 0.0025) - tau).norm(), 1e-15);
}

TEST(RunTimeSize, ConversionToAFixedCountChecksTheCount) {
  const DynModel model = load_robot<double, Eigen::Dynamic>(data_path("arm4.robot.json"));
  const Arm fixed = joint_count_cast<4>(model);
  EXPECT_EQ(fixed.joint_names, arm().joint_names);
  EXPECT_EQ(fixed.torque_constant, arm().torque_constant);
  const DynModel back = joint_count_cast<Eigen::Dynamic>(fixed);
  EXPECT_EQ(back.joint_count(), 4);
  EXPECT_TRUE(back.constants_current());
  try {
    (void)joint_count_cast<7>(model);
    FAIL() << "a 4-joint model converted to 7 joints";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("has 4 joints"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tpf::test
