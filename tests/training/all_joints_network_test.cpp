// The one network for all joints as the offline tools evaluate it (AllJointsNetwork, sizes at run
// time) against the compiled Tcn a 4-joint controller runs (AllJointsTcn<32>), and the same
// network shape for 9 joints, which no compiled count covers.
#include "offline/replay/all_joints_network.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "offline/compensator_training/tcn_parameters.hpp"
#include "offline/replay/any_compensator.hpp"
#include "tpf/common/error.hpp"
#include "tpf/nn/load_tcn_weights.hpp"

namespace tpf::offline {
namespace {

/// An untrained all-joints network of `joints` joints (He-initialised, seeded) with a
/// normalisation that is not the identity, as a weight file.
TcnWeightFile all_joints_file(int joints, std::uint64_t seed) {
  TcnArchitecture a;
  a.inputs = kCompensatorInputsPerJoint * joints;
  a.hidden = kAllJointsHidden;
  a.outputs = joints;
  TcnParameters p = init_tcn_parameters(a, seed);
  p.input_mean = Eigen::VectorXd::LinSpaced(a.inputs, -0.5, 0.8);
  p.input_std = Eigen::VectorXd::LinSpaced(a.inputs, 0.3, 2.5);
  return to_weight_file(p);
}

/// Input k of a smooth, distinct sequence of n values.
Eigen::VectorXd input(int n, int k) {
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i)
    x[i] = std::sin(0.05 * k * (i + 1) + i) * (1.0 + 0.1 * i);
  return x;
}

TEST(AllJointsNetwork, EqualsTheCompiledNetworkOfFourJointsToRounding) {
  constexpr int kJoints = 4;
  using Compiled = AllJointsTcn<kAllJointsHidden>::For<double, kJoints>;
  const TcnWeightFile file = all_joints_file(kJoints, 17);
  auto compiled = std::make_unique<Compiled>();
  tcn_weights_from_file(file, *compiled);
  compiled->reset(Eigen::Map<const Eigen::VectorXd>(file.input_mean.data(), 5 * kJoints));
  AllJointsNetwork run_time;
  run_time.load(file, kJoints, kAllJointsHidden, kCompensatorLevels, kCompensatorKernel);
  EXPECT_EQ(run_time.receptive_field(), Compiled::kReceptiveField);

  double largest = 0.0;
  for (int k = 0; k < 300; ++k) {
    Eigen::VectorXd x = input(5 * kJoints, k);
    if (k == 120) x[3] = std::numeric_limits<double>::quiet_NaN();  // replaced by the last finite
    if (k == 200) {
      compiled->reset(x);
      run_time.reset(x);
    }
    const Eigen::VectorXd expected = compiled->step(x);
    const Eigen::VectorXd got = run_time.step(x);
    ASSERT_EQ(got.size(), kJoints);
    ASSERT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + expected.norm()))
        << "step " << k;
    largest = std::max(largest, expected.cwiseAbs().maxCoeff());
  }
  EXPECT_GT(largest, 1e-3) << "the network's output must not be trivially zero";
}

TEST(AllJointsNetwork, RunsNineJointsAndRefusesAnotherCount) {
  const TcnWeightFile file = all_joints_file(9, 3);
  AllJointsNetwork net;
  net.load(file, 9, kAllJointsHidden, kCompensatorLevels, kCompensatorKernel);
  // Its history matters: a constant input gives the steady output reset() prewarms, a varying
  // one does not.
  const Eigen::VectorXd steady = input(45, 7);
  net.reset(steady);
  const Eigen::VectorXd at_rest = net.step(steady);
  ASSERT_EQ(at_rest.size(), 9);
  for (int k = 0; k < 50; ++k)
    EXPECT_LT((net.step(steady) - at_rest).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT((net.step(input(45, 60)) - at_rest).cwiseAbs().maxCoeff(), 1e-6);

  AllJointsNetwork eight;
  try {
    eight.load(file, 8, kAllJointsHidden, kCompensatorLevels, kCompensatorKernel);
    ADD_FAILURE() << "a 9-joint network loaded for 8 joints";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("architecture.inputs: 45 in the file, 40 expected"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tpf::offline
