#include "tpf/dynamics/base_parameters.hpp"

#include <gtest/gtest.h>

#include "support/arm_fixture.hpp"

namespace tpf::test {
namespace {

Eigen::MatrixXd stacked_regressor(RandomStates& rs, int samples) {
  ArmData data;
  Regressor<double, kJoints> Y;
  Eigen::MatrixXd W(samples * kJoints, regressor_columns<kJoints>);
  for (int s = 0; s < samples; ++s) {
    compute_regressor(arm(), data, rs.vector(3.0), rs.vector(2.0), rs.vector(5.0), Y);
    W.middleRows(s * kJoints, kJoints) = Y;
  }
  return W;
}

TEST(BaseParameters, ReducedRegressorReproducesTheTorquesAtNewStates) {
  RandomStates rs(31);
  const BaseParameters base = find_base_parameters(stacked_regressor(rs, 200));
  // A 4-joint arm cannot identify all 52 parameters: link 1 rotates about a fixed vertical axis,
  // etc.
  EXPECT_LT(base.size(), regressor_columns<kJoints>);
  EXPECT_GT(base.size(), 3 * kJoints);  // at least armature + friction + something per link
  const Vec coulomb = Vec::Constant(0.3), viscous = Vec::Constant(1.5);
  const Eigen::VectorXd pi = dynamic_parameters(arm(), coulomb, viscous);
  const Eigen::VectorXd pi_b = base.project(pi);
  const Eigen::MatrixXd W = stacked_regressor(rs, 50);  // fresh states
  EXPECT_LT((base.reduce(W) * pi_b - W * pi).norm(), 1e-9 * (W * pi).norm());
  // and the reduced regressor has full column rank
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(base.reduce(W));
  EXPECT_EQ(qr.rank(), base.size());
}

TEST(BaseParameters, RankIsTheSameForAnotherSeed) {
  RandomStates a(41), b(42);
  EXPECT_EQ(find_base_parameters(stacked_regressor(a, 150)).size(),
            find_base_parameters(stacked_regressor(b, 150)).size());
}

}  // namespace
}  // namespace tpf::test
