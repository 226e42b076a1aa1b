// tpf against orocos-kdl on the same robots, the same maths: KDL's joints carry tpf's armature
// (rotor inertia reflected to the output) as their `inertia`, so torques, gravity, mass matrix,
// velocity torques and Jacobians must agree to rounding (1e-12), for the 4-DoF arm and the 7-DoF
// Kinova Gen3.
#include <gtest/gtest.h>

#include <kdl/chaindynparam.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <random>

#include "support/arm_fixture.hpp"
#include "support/kdl_arm.hpp"

namespace tpf::test {
namespace {

constexpr double kAgreement = 1e-12;

/// One robot as tpf loads it and as KDL parses its URDF, armature included in both.
template <int N>
struct PeerRobot {
  using Vec = JointVector<double, N>;
  Model<double, N> model;
  KDL::Chain chain;
  KDL::Vector gravity;

  PeerRobot(const std::string& robot_file, const std::string& urdf, const std::string& base,
            const std::string& tip)
      : model(load_robot<double, N>(data_path(robot_file))),
        chain(with_armature(kdl_chain(data_path(urdf), base, tip), model.armature)),
        gravity(model.gravity.x(), model.gravity.y(), model.gravity.z()) {}

  static KDL::JntArray to_kdl(const Vec& v) {
    KDL::JntArray a(N);
    a.data = v;
    return a;
  }
};

PeerRobot<4> arm4() {
  return {"arm4.robot.json", "arm4.urdf", "link1", "link5"};
}
PeerRobot<7> gen3() {
  return {"real/kinova-gen3/gen3.robot.json", "real/kinova-gen3/gen3.urdf", "base_link",
          "end_effector_link"};
}

template <int N>
void expect_inverse_dynamics_agree(const PeerRobot<N>& robot, unsigned seed) {
  using R = PeerRobot<N>;
  ASSERT_EQ(robot.chain.getNrOfJoints(), static_cast<unsigned>(N));
  ASSERT_GT(robot.model.armature.minCoeff(), 0.0);  // the comparison includes the armature
  KDL::ChainIdSolver_RNE solver(robot.chain, robot.gravity);
  Data<double, N> data;
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < 100; ++trial) {
    const auto q = random_vector<N>(rng, 3.0), dq = random_vector<N>(rng, 2.0),
               ddq = random_vector<N>(rng, 5.0);
    KDL::JntArray tau(N);
    KDL::Wrenches no_wrench(robot.chain.getNrOfSegments(), KDL::Wrench::Zero());
    ASSERT_GE(solver.CartToJnt(R::to_kdl(q), R::to_kdl(dq), R::to_kdl(ddq), no_wrench, tau), 0);
    EXPECT_LT((rnea(robot.model, data, q, dq, ddq) - tau.data).norm(), kAgreement);
  }
}

template <int N>
void expect_gravity_mass_matrix_and_velocity_torques_agree(const PeerRobot<N>& robot,
                                                           unsigned seed) {
  using R = PeerRobot<N>;
  KDL::ChainDynParam dyn(robot.chain, robot.gravity);
  Data<double, N> data;
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < 100; ++trial) {
    const auto q = random_vector<N>(rng, 3.0), dq = random_vector<N>(rng, 2.0);
    KDL::JntArray g(N), c(N);
    KDL::JntSpaceInertiaMatrix M(N);
    dyn.JntToGravity(R::to_kdl(q), g);
    dyn.JntToMass(R::to_kdl(q), M);
    dyn.JntToCoriolis(R::to_kdl(q), R::to_kdl(dq), c);
    EXPECT_LT((compute_gravity(robot.model, data, q) - g.data).norm(), kAgreement);
    EXPECT_LT((compute_mass_matrix(robot.model, data, q) - M.data).norm(), kAgreement);
    EXPECT_LT((velocity_torques(robot.model, data, q, dq) - c.data).norm(), kAgreement);
  }
}

/// The Jacobian at `point` (link frame) of every moving link, KDL's reference point moved from
/// the segment origin to it.
template <int N>
void expect_point_jacobians_agree(const PeerRobot<N>& robot, const Vector3<double>& point,
                                  unsigned seed) {
  using R = PeerRobot<N>;
  KDL::ChainJntToJacSolver jac_solver(robot.chain);
  Data<double, N> data;
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < 50; ++trial) {
    const auto q = random_vector<N>(rng, 3.0);
    forward_kinematics(robot.model, data, q);
    for (int link = 1; link <= N; ++link) {
      KDL::Jacobian J(N);
      ASSERT_GE(jac_solver.JntToJac(R::to_kdl(q), J, link), 0);
      const Vector3<double> p = data.oMi[link].apply(point);
      const Vector3<double> offset = p - data.oMi[link].p;
      J.changeRefPoint(KDL::Vector(offset.x(), offset.y(), offset.z()));
      EXPECT_LT((point_jacobian(robot.model, data, link, p) - J.data).norm(), kAgreement)
          << "link " << link;
    }
  }
}

TEST(KdlAgreement, Arm4InverseDynamicsWithArmature) {
  expect_inverse_dynamics_agree(arm4(), 51);
}
TEST(KdlAgreement, Gen3InverseDynamicsWithArmature) {
  expect_inverse_dynamics_agree(gen3(), 61);
}

TEST(KdlAgreement, Arm4GravityMassMatrixVelocityTorques) {
  expect_gravity_mass_matrix_and_velocity_torques_agree(arm4(), 52);
}
TEST(KdlAgreement, Gen3GravityMassMatrixVelocityTorques) {
  expect_gravity_mass_matrix_and_velocity_torques_agree(gen3(), 62);
}

TEST(KdlAgreement, Arm4JacobianAtEveryPad) {
  const PeerRobot<4> robot = arm4();
  KDL::ChainJntToJacSolver jac_solver(robot.chain);
  Data<double, 4> data;
  std::mt19937_64 rng(53);
  const std::vector<Pad> pads = load_pads(data_path("arm4.pads.json"), robot.model);
  ASSERT_FALSE(pads.empty());
  for (int trial = 0; trial < 50; ++trial) {
    const auto q = random_vector<4>(rng, 3.0);
    forward_kinematics(robot.model, data, q);
    for (const Pad& pad : pads) {
      KDL::Jacobian J(4);
      ASSERT_GE(jac_solver.JntToJac(PeerRobot<4>::to_kdl(q), J, pad.link), 0);
      const Vector3<double> p = data.oMi[pad.link].apply(pad.center);
      const Vector3<double> offset = p - data.oMi[pad.link].p;
      J.changeRefPoint(KDL::Vector(offset.x(), offset.y(), offset.z()));
      EXPECT_LT((point_jacobian(robot.model, data, pad.link, p) - J.data).norm(), kAgreement)
          << pad.name;
    }
  }
}

TEST(KdlAgreement, Gen3JacobianAtAPointOfEveryLink) {
  expect_point_jacobians_agree(gen3(), Vector3<double>(0.03, -0.02, 0.05), 63);
}

TEST(KdlAgreement, Gen3LinkPosesMatchKdlForwardKinematics) {
  const PeerRobot<7> robot = gen3();
  KDL::ChainFkSolverPos_recursive fk(robot.chain);
  Data<double, 7> data;
  std::mt19937_64 rng(64);
  for (int trial = 0; trial < 50; ++trial) {
    const auto q = random_vector<7>(rng, 3.0);
    forward_kinematics(robot.model, data, q);
    for (int link = 1; link <= 7; ++link) {
      KDL::Frame pose;
      ASSERT_GE(fk.JntToCart(PeerRobot<7>::to_kdl(q), pose, link), 0);
      for (int r = 0; r < 3; ++r) {
        EXPECT_NEAR(data.oMi[link].p(r), pose.p(r), kAgreement);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(data.oMi[link].R(r, c), pose.M(r, c), kAgreement);
      }
    }
  }
}

}  // namespace
}  // namespace tpf::test
