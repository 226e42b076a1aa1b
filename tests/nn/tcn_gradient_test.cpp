// Backpropagation through the full-window TCN against central finite differences, every tensor.
#include <gtest/gtest.h>

#include "offline/compensator_training/tcn_window_model.hpp"
#include "tcn_test_support.hpp"

namespace tpf::offline {
namespace {

void expect_gradient_matches_finite_differences(const TcnArchitecture& a, std::uint64_t seed,
                                                bool weighted = false) {
  TcnParameters p = test::random_tcn_parameters(a, seed);
  p.input_mean.setZero();  // the window model takes normalised inputs
  p.input_std.setOnes();
  const Eigen::Index outputs = 9, width = a.receptive_field() - 1 + outputs;
  const Eigen::MatrixXd x = test::random_inputs(a.inputs, width, seed + 1);
  const Eigen::MatrixXd low = test::random_inputs(a.outputs, outputs, seed + 2);
  const Eigen::MatrixXd high = test::random_inputs(a.outputs, outputs, seed + 3);
  const double w_low = 0.7, w_high = 1.9;
  const Eigen::MatrixXd scale =
      (test::random_inputs(a.outputs, outputs, seed + 4).array().abs() + 0.1).matrix();
  const TcnWindowMatrix<double> scale_ref = scale;
  const TcnWindowMatrix<double>* s = weighted ? &scale_ref : nullptr;

  TcnWindowWorkspace ws;
  TcnParameters g = zero_tcn_parameters(a);
  tcn_window_loss(p, x, low, high, w_low, w_high, ws, &g, s);
  const Eigen::VectorXd analytic = flatten(g);

  std::vector<std::string> names;
  for_each_tcn_tensor(p, [&](const std::string& name, double*, Eigen::Index size) {
    for (Eigen::Index i = 0; i < size; ++i)
      names.push_back(name + "[" + std::to_string(i) + "]");
  });
  ASSERT_EQ(static_cast<Eigen::Index>(names.size()), tcn_parameter_count(a));

  Eigen::VectorXd theta = flatten(p);
  const double h = 1e-6;
  int nonzero = 0;
  for (Eigen::Index k = 0; k < theta.size(); ++k) {
    const double saved = theta[k];
    theta[k] = saved + h;
    unflatten(theta, p);
    const double up = tcn_window_loss(p, x, low, high, w_low, w_high, ws, nullptr, s);
    theta[k] = saved - h;
    unflatten(theta, p);
    const double down = tcn_window_loss(p, x, low, high, w_low, w_high, ws, nullptr, s);
    theta[k] = saved;
    const double numeric = (up - down) / (2 * h);
    EXPECT_NEAR(analytic[k], numeric, 1e-6 * (1.0 + std::abs(numeric))) << names[k];
    nonzero += std::abs(analytic[k]) > 1e-8;
  }
  EXPECT_GT(nonzero, theta.size() / 2);  // most units alive: the check is not vacuous
}

TEST(TcnGradient, EveryTensorMatchesFiniteDifferencesWithProjection) {
  expect_gradient_matches_finite_differences({3, 5, 3, 3, 2}, 101);
}

TEST(TcnGradient, EveryTensorMatchesFiniteDifferencesWithIdentitySkip) {
  expect_gradient_matches_finite_differences({4, 4, 2, 4, 1}, 202);
}

TEST(TcnGradient, EveryTensorMatchesFiniteDifferencesWithSampleWeights) {
  expect_gradient_matches_finite_differences({3, 5, 3, 3, 2}, 505, true);
}

TEST(TcnGradient, SampleScaleWeighsTheLossAndItsGradient) {
  const TcnArchitecture a{4, 6, 2, 3, 2};
  const TcnParameters p = test::random_tcn_parameters(a, 606);
  const Eigen::Index outputs = 12, width = a.receptive_field() - 1 + outputs;
  const Eigen::MatrixXd x = test::random_inputs(a.inputs, width, 607);
  const Eigen::MatrixXd low = test::random_inputs(a.outputs, outputs, 608);
  Eigen::MatrixXd high = test::random_inputs(a.outputs, outputs, 609);
  Eigen::MatrixXd scale = (test::random_inputs(a.outputs, outputs, 610).array().abs()).matrix();
  scale.col(3).setZero();
  TcnWindowWorkspace ws;
  tcn_window_forward(p, x, ws);
  const double expected = 0.5 * (scale.cwiseProduct(ws.low - low)).squaredNorm() +
                          2.0 * (scale.cwiseProduct(ws.high - high)).squaredNorm();
  const TcnWindowMatrix<double> s = scale;
  TcnParameters g1 = zero_tcn_parameters(a), g2 = zero_tcn_parameters(a);
  EXPECT_NEAR(tcn_window_loss(p, x, low, high, 0.5, 2.0, ws, &g1, &s), expected, 1e-12 * expected);
  // A zero-weight sample is ignored whatever its target.
  high.col(3).array() += 100.0;
  EXPECT_NEAR(tcn_window_loss(p, x, low, high, 0.5, 2.0, ws, &g2, &s), expected, 1e-12 * expected);
  EXPECT_EQ(flatten(g1), flatten(g2));
}

TEST(TcnGradient, WindowForwardEqualsNaiveNetwork) {
  const TcnArchitecture a{4, 8, 3, 4, 2};
  TcnParameters p = test::random_tcn_parameters(a, 303);
  const Eigen::MatrixXd raw = test::random_inputs(4, a.receptive_field() + 40, 304);
  const Eigen::MatrixXd normalised =
      (raw.colwise() - p.input_mean).array().colwise() / p.input_std.array();
  TcnWindowWorkspace ws;
  tcn_window_forward(p, normalised, ws);
  const Eigen::MatrixXd naive = test::naive_tcn(p, raw);
  EXPECT_LT((ws.low - naive.topRows(2)).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((ws.high - naive.bottomRows(2)).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace tpf::offline

namespace tpf::offline {
namespace {

TEST(TcnGradient, FloatEvaluationTracksDouble) {
  const TcnArchitecture a{4, 16, 3, 4, 1};
  TcnParameters p = test::random_tcn_parameters(a, 404);
  const Eigen::Index outputs = 50, width = a.receptive_field() - 1 + outputs;
  const Eigen::MatrixXd x = test::random_inputs(a.inputs, width, 405);
  const Eigen::MatrixXd low = test::random_inputs(1, outputs, 406);
  const Eigen::MatrixXd high = test::random_inputs(1, outputs, 407);
  TcnWindowWorkspace wd;
  BasicTcnWindowWorkspace<float> wf;
  TcnParameters gd = zero_tcn_parameters(a);
  BasicTcnParameters<float> gf = gd.cast<float>();
  const double ld = tcn_window_loss(p, x, low, high, 1.0, 2.0, wd, &gd);
  const double lf = tcn_window_loss(p.cast<float>(), x.cast<float>(), low.cast<float>(),
                                    high.cast<float>(), 1.0, 2.0, wf, &gf);
  EXPECT_NEAR(lf, ld, 1e-4 * ld);
  TcnParameters gf_double = gf.cast<double>();
  const Eigen::VectorXd a_d = flatten(gd), a_f = flatten(gf_double);
  EXPECT_LT((a_f - a_d).norm(), 1e-4 * a_d.norm());
}

}  // namespace
}  // namespace tpf::offline
