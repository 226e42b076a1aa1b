#include <gtest/gtest.h>

#include <kdl/chaindynparam.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include "support/arm_fixture.hpp"
#include "support/kdl_arm.hpp"

namespace tpf::test {
namespace {

KDL::JntArray to_kdl(const Vec& v) {
  KDL::JntArray a(kJoints);
  a.data = v;
  return a;
}

/// KDL knows no armature: compare the rigid-body part.
Arm rigid_arm() {
  Arm model = arm();
  model.armature.setZero();
  return model;
}

class KdlAgreement : public ::testing::Test {
 protected:
  const Arm model = rigid_arm();
  const KDL::Chain chain = kdl_chain(data_path("arm4.urdf"), "link1", "link5");
  KDL::Vector gravity{0, 0, -9.81};
};

TEST_F(KdlAgreement, InverseDynamicsTorques) {
  ASSERT_EQ(chain.getNrOfJoints(), static_cast<unsigned>(kJoints));
  KDL::ChainIdSolver_RNE solver(chain, gravity);
  ArmData data;
  RandomStates rs(51);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec q = rs.vector(3.0), dq = rs.vector(2.0), ddq = rs.vector(5.0);
    KDL::JntArray tau(kJoints);
    KDL::Wrenches no_wrench(chain.getNrOfSegments(), KDL::Wrench::Zero());
    ASSERT_GE(solver.CartToJnt(to_kdl(q), to_kdl(dq), to_kdl(ddq), no_wrench, tau), 0);
    EXPECT_LT((rnea(model, data, q, dq, ddq) - tau.data).norm(), 1e-9);
  }
}

TEST_F(KdlAgreement, GravityAndMassMatrix) {
  KDL::ChainDynParam dyn(chain, gravity);
  ArmData data;
  RandomStates rs(52);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec q = rs.vector(3.0), dq = rs.vector(2.0);
    KDL::JntArray g(kJoints), c(kJoints);
    KDL::JntSpaceInertiaMatrix M(kJoints);
    dyn.JntToGravity(to_kdl(q), g);
    dyn.JntToMass(to_kdl(q), M);
    dyn.JntToCoriolis(to_kdl(q), to_kdl(dq), c);
    EXPECT_LT((compute_gravity(model, data, q) - g.data).norm(), 1e-9);
    EXPECT_LT((compute_mass_matrix(model, data, q) - M.data).norm(), 1e-9);
    EXPECT_LT((velocity_torques(model, data, q, dq) - c.data).norm(), 1e-9);
  }
}

TEST_F(KdlAgreement, JacobianAtTipAndAtEveryPad) {
  KDL::ChainJntToJacSolver jac_solver(chain);
  ArmData data;
  RandomStates rs(53);
  const std::vector<Pad> pads = load_pads(data_path("arm4.pads.json"), model);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec q = rs.vector(3.0);
    forward_kinematics(model, data, q);
    for (const Pad& pad : pads) {
      // KDL's Jacobian of segment `link` (1-based), reference point moved from the segment's
      // origin to the pad centre, both in the base frame.
      KDL::Jacobian J(kJoints);
      ASSERT_GE(jac_solver.JntToJac(to_kdl(q), J, pad.link), 0);
      const Vector3<double> p = data.oMi[pad.link].apply(pad.center);
      const Vector3<double> offset = p - data.oMi[pad.link].p;
      J.changeRefPoint(KDL::Vector(offset.x(), offset.y(), offset.z()));
      EXPECT_LT((point_jacobian(model, data, pad.link, p) - J.data).norm(), 1e-9) << pad.name;
    }
  }
}

}  // namespace
}  // namespace tpf::test
