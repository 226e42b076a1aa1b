// PerJointTcnCompensator: network j sees exactly joint j's inputs and its output is τ_TCN,j.
#include <gtest/gtest.h>

#include <limits>
#include <memory>

#include "support/allocation_counter.hpp"
#include "tcn_test_support.hpp"
#include "tpf/nn/per_joint_tcn_compensator.hpp"

namespace tpf {
namespace {

constexpr int kJoints = 3;
using PerJoint = PerJointTcnCompensator<double, kJoints, 8, 3>;

TEST(PerJointTcn, EachJointRunsItsOwnNetworkOnItsOwnInputs) {
  const offline::TcnArchitecture a{kCompensatorInputsPerJoint, 8, 3, 4, 1};
  auto bank = std::make_unique<PerJoint>();
  std::array<PerJoint::Network, kJoints> alone{};
  for (int j = 0; j < kJoints; ++j) {
    const offline::TcnParameters p = test::random_tcn_parameters(a, 40 + j);
    test::load_parameters(p, bank->network(j));
    test::load_parameters(p, alone[j]);
  }
  // x = [q; q̇; q̈; τ̂_fric,s; τ_fric,nom], each block N long.
  const Eigen::MatrixXd raw = test::random_inputs(kCompensatorInputsPerJoint * kJoints, 80, 50);
  const auto joint_column = [&](Eigen::Index t, int j) {
    return Eigen::Matrix<double, 5, 1>(raw(j, t), raw(kJoints + j, t), raw(2 * kJoints + j, t),
                                       raw(3 * kJoints + j, t), raw(4 * kJoints + j, t));
  };
  bank->reset(raw.col(0));
  for (int j = 0; j < kJoints; ++j)
    alone[j].reset(joint_column(0, j));
  double largest = 0.0;
  for (Eigen::Index t = 1; t < raw.cols(); ++t) {
    const PerJoint::Input x = raw.col(t);
    test::AllocationCounter allocations;
    const PerJoint::Output& y = bank->step(x);
    EXPECT_EQ(allocations.count(), 0u);
    for (int j = 0; j < kJoints; ++j) {
      EXPECT_EQ(y[j], alone[j].step(joint_column(t, j))[0]) << "t = " << t << ", joint " << j;
      largest = std::max(largest, std::abs(y[j]));
    }
  }
  EXPECT_GT(largest, 0.1);  // dead networks would prove nothing
  // Swapping two joints' inputs changes both outputs: no joint sees another's channel.
  PerJoint::Input swapped = raw.col(5);
  std::swap(swapped[0], swapped[1]);
  auto other = std::make_unique<PerJoint>(*bank);
  EXPECT_NE(bank->step(raw.col(5))[0], other->step(swapped)[0]);
}

// Float networks behind the double interface (what the tools ship): the same weights give the
// double networks' outputs to float precision, and the step still allocates nothing.
TEST(PerJointTcn, FloatNetworksMatchTheDoubleOnesToFloatPrecision) {
  using FloatNetworks = PerJointTcnCompensator<double, kJoints, 8, 3, float>;
  const offline::TcnArchitecture a{kCompensatorInputsPerJoint, 8, 3, 4, 1};
  auto exact = std::make_unique<PerJoint>();
  auto rounded = std::make_unique<FloatNetworks>();
  for (int j = 0; j < kJoints; ++j) {
    const offline::TcnParameters p = test::random_tcn_parameters(a, 60 + j);
    test::load_parameters(p, exact->network(j));
    test::load_parameters(p, rounded->network(j));
  }
  const Eigen::MatrixXd raw = test::random_inputs(kCompensatorInputsPerJoint * kJoints, 120, 61);
  exact->reset(raw.col(0));
  rounded->reset(raw.col(0));
  double largest = 0.0, worst = 0.0;
  for (Eigen::Index t = 1; t < raw.cols(); ++t) {
    const PerJoint::Input x = raw.col(t);
    const PerJoint::Output y = exact->step(x);
    test::AllocationCounter allocations;
    const FloatNetworks::Output& z = rounded->step(x);
    EXPECT_EQ(allocations.count(), 0u);
    largest = std::max(largest, y.cwiseAbs().maxCoeff());
    worst = std::max(worst, (z - y).cwiseAbs().maxCoeff());
  }
  EXPECT_GT(largest, 0.1);
  EXPECT_GT(worst, 0.0);             // it really ran in float
  EXPECT_LT(worst, 1e-5 * largest);  // ≈ 2^-24 per operation, a few hundred operations deep
}

// The networks step together, interleaved (Tcn::step_together): bit for bit what stepping each
// alone gives, for the shipped shape (float, 16 channels, 4 levels) with 4 and 7 joints (7 leaves
// a group remainder), across a non-finite sample, with no allocation.
template <int Joints>
void expect_interleaved_equals_alone() {
  using Bank = PerJointTcnCompensator<double, Joints, 16, 4, float>;
  const offline::TcnArchitecture a{kCompensatorInputsPerJoint, 16, 4, 4, 1};
  auto bank = std::make_unique<Bank>();
  auto alone = std::make_unique<std::array<typename Bank::Network, Joints>>();
  for (int j = 0; j < Joints; ++j) {
    const offline::TcnParameters p = test::random_tcn_parameters(a, 70 + j);
    test::load_parameters(p, bank->network(j));
    test::load_parameters(p, (*alone)[j]);
  }
  Eigen::MatrixXd raw = test::random_inputs(kCompensatorInputsPerJoint * Joints, 120, 71);
  raw(Joints + 1, 60) = std::numeric_limits<double>::quiet_NaN();
  bank->reset(raw.col(0));
  for (int j = 0; j < Joints; ++j)
    (*alone)[j].reset(Bank::joint_input(raw.col(0), j));
  double largest = 0.0;
  for (Eigen::Index t = 1; t < raw.cols(); ++t) {
    const typename Bank::Input x = raw.col(t);
    test::AllocationCounter allocations;
    const typename Bank::Output& y = bank->step(x);
    EXPECT_EQ(allocations.count(), 0u);
    for (int j = 0; j < Joints; ++j) {
      const float expected = (*alone)[j].step(Bank::joint_input(x, j))[0];
      EXPECT_EQ(y[j], static_cast<double>(expected)) << "t = " << t << ", joint " << j;
      EXPECT_EQ(bank->network(j).low(), (*alone)[j].low());
      largest = std::max(largest, std::abs(y[j]));
    }
  }
  EXPECT_EQ(bank->network(1).skipped_inputs(), 1);
  EXPECT_GT(largest, 0.1);
}

TEST(PerJointTcn, InterleavedStepEqualsEachNetworkAloneBitForBit) {
  expect_interleaved_equals_alone<4>();
  expect_interleaved_equals_alone<7>();
}

}  // namespace
}  // namespace tpf
