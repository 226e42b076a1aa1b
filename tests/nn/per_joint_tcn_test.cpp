// PerJointTcn: network j sees exactly joint j's inputs and its output is τ_TCN,j.
#include "tpf/nn/per_joint_tcn.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "support/allocation_counter.hpp"
#include "tcn_test_support.hpp"

namespace tpf {
namespace {

constexpr int kJoints = 3;
using PerJoint = PerJointTcn<double, kJoints, 8, 3>;

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

}  // namespace
}  // namespace tpf
