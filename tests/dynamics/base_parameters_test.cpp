#include "tpf/dynamics/base_parameters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

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

TEST(BaseParameters, AStructurallyZeroColumnIsNoBaseParameter) {
  // A column that is zero but for rounding (~1e-14, as a term that cancels on some arms): scaled
  // to unit norm it looks independent, and its base parameter fits the noise divided by 1e-14.
  RandomStates rs(51);
  Eigen::MatrixXd W = stacked_regressor(rs, 200);
  const BaseParameters clean = find_base_parameters(W);
  int zero = -1;  // a column of W that is no base parameter (dependent or zero)
  for (int c = 0; c < W.cols() && zero < 0; ++c)
    if (!std::binary_search(clean.independent.begin(), clean.independent.end(), c)) zero = c;
  ASSERT_GE(zero, 0);
  std::mt19937_64 rng(52);
  std::normal_distribution<double> unit;
  for (Eigen::Index r = 0; r < W.rows(); ++r)
    W(r, zero) = 1e-14 * unit(rng);
  const BaseParameters base = find_base_parameters(W);
  EXPECT_EQ(base.independent, clean.independent);
  EXPECT_TRUE(base.beta.col(zero).isZero(0.0));
  // Least squares of torques with a little noise on the base columns: every parameter stays of
  // the size of the arm's own (a base parameter of the planted column fits the noise / 1e-14).
  const Eigen::VectorXd pi =
      dynamic_parameters(arm(), Vec::Constant(0.3), Vec::Constant(1.5)).head(W.cols());
  Eigen::VectorXd tau = W * pi;
  for (Eigen::Index r = 0; r < tau.size(); ++r)
    tau[r] += 1e-6 * unit(rng);
  const Eigen::VectorXd fitted = base.reduce(W).colPivHouseholderQr().solve(tau);
  EXPECT_LT(fitted.cwiseAbs().maxCoeff(), 1e3 * std::max(1.0, pi.cwiseAbs().maxCoeff()));
  EXPECT_LT((fitted - base.project(pi)).cwiseAbs().maxCoeff(), 1e-3);
}

TEST(BaseParameters, OfAnArmWithContinuousJoints) {
  // The Gen3's joints 1, 3, 5 and 7 turn without limits (±∞ in the model): the base parameters
  // are found from poses over a whole turn of those joints, and the reduced regressor reproduces
  // the rigid-body torques of the robot file's inertias at fresh poses anywhere.
  constexpr int N = 7;
  const Model<double, N> model =
      load_robot<double, N>(data_path("real/kinova-gen3/gen3.robot.json"));
  ASSERT_FALSE(model.has_position_limits(0));
  ASSERT_TRUE(model.has_position_limits(1));
  const BaseParameters base = rigid_body_base_parameters(model);
  EXPECT_GT(base.size(), 5 * N);  // ≥ 5 identifiable combinations per link and its armature
  EXPECT_LT(base.size(), 11 * N);
  const Eigen::VectorXd pi =
      dynamic_parameters(model, JointVector<double, N>::Zero(), JointVector<double, N>::Zero())
          .head(11 * N);
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Data<double, N> data;
  Regressor<double, N> Y;
  Eigen::MatrixXd W(50 * N, 11 * N);
  for (int s = 0; s < 50; ++s) {
    JointVector<double, N> q, dq, ddq;
    for (int j = 0; j < N; ++j) {
      q[j] = 6.0 * unit(rng);
      dq[j] = 2.0 * unit(rng);
      ddq[j] = 5.0 * unit(rng);
    }
    compute_regressor(model, data, q, dq, ddq, Y);
    W.middleRows(s * N, N) = Y.leftCols(11 * N);
  }
  ASSERT_TRUE(W.allFinite());
  EXPECT_LT((base.reduce(W) * base.project(pi) - W * pi).norm(), 1e-9 * (W * pi).norm());
}

}  // namespace
}  // namespace tpf::test
