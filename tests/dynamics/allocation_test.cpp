#include <gtest/gtest.h>

#include "support/allocation_counter.hpp"
#include "support/arm_fixture.hpp"

namespace tpf::test {
namespace {

TEST(PerCycle, KinematicsAndDynamicsAllocateNothing) {
  const Arm& model = arm();
  ArmData data(model);
  RandomStates rs(21);
  const Vec q = rs.vector(2.0), dq = rs.vector(1.0), ddq = rs.vector(3.0);
  Jacobian<double, kJoints> J;
  Regressor<double, kJoints> Y;
  Vector6<double> w = Vector6<double>::Ones();
  AllocationCounter counter;
  forward_kinematics(model, data, q);
  point_jacobian(model, data, 3, Vector3<double>(0.1, 0.0, 0.4), J);
  rnea(model, data, q, dq, ddq);
  rnea(model, data, q, dq, ddq, 3, Vector3<double>(0.1, 0.0, 0.4), w);
  compute_gravity(model, data, q);
  compute_mass_matrix(model, data, q);
  compute_coriolis_matrix(model, data, q, dq);
  forward_dynamics(model, data, q, dq, ddq);
  compute_regressor(model, data, q, dq, ddq, Y);
  EXPECT_EQ(counter.count(), 0u);
}

TEST(PerCycle, TheCounterSeesAnAllocation) {
  AllocationCounter counter;
  auto* v = new std::vector<double>(16);
  delete v;
  EXPECT_GE(counter.count(), 1u);  // the proof above would catch one
}

TEST(PerCycle, FloatModelAgreesWithDouble) {
  const Model<float, kJoints> model = arm().cast<float>();
  Data<float, kJoints> data;
  ArmData reference;
  RandomStates rs(22);
  const Vec q = rs.vector(2.0), dq = rs.vector(1.0), ddq = rs.vector(3.0);
  const Vec tau = rnea(arm(), reference, q, dq, ddq);
  const JointVector<float, kJoints> tau_f =
      rnea(model, data, JointVector<float, kJoints>(q.cast<float>()),
           JointVector<float, kJoints>(dq.cast<float>()),
           JointVector<float, kJoints>(ddq.cast<float>()));
  EXPECT_LT((tau_f.cast<double>() - tau).norm(), 1e-4 * (1 + tau.norm()));
}

}  // namespace
}  // namespace tpf::test
