// The Stribeck curve fit: its analytic Jacobian against finite differences, and the recovery of a
// known curve written out independently of the fit's cost.
#include "offline/identify/stribeck_fit.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "offline/identify/stribeck_curve_cost.hpp"

namespace tpf::offline {
namespace {

struct CurveSamples {
  Eigen::VectorXd dq, abs_gravity, friction;
};

// Moving samples of both directions, 0.004–1.5 rad/s, |G| in 0–20 N·m, of the curve
// f = [τ_c + α_c|G| + (τ_s − τ_c)·exp(−(|q̇|/q̇_s)^δ)]·sgn q̇ + (b + α_v|G|)·q̇.
CurveSamples sample_curve(const JointStribeck& c, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> log_speed(std::log(0.004), std::log(1.5));
  std::uniform_real_distribution<double> load(0.0, 20.0);
  CurveSamples s{Eigen::VectorXd(count), Eigen::VectorXd(count), Eigen::VectorXd(count)};
  for (int k = 0; k < count; ++k) {
    const double speed = std::exp(log_speed(rng));
    const double v = (k % 2 == 0) ? speed : -speed;
    const double g = load(rng);
    const double level = c.coulomb + c.load_coulomb * g +
                         (c.static_friction - c.coulomb) *
                             std::exp(-std::pow(speed / c.stribeck_velocity, c.stribeck_exponent));
    s.dq[k] = v;
    s.abs_gravity[k] = g;
    s.friction[k] = std::copysign(level, v) + (c.viscous + c.load_viscous * g) * v;
  }
  return s;
}

// The plain residuals and the Cauchy-robustified ones (scale 0.3 N·m, residuals up to ≈ 3 N·m).
class StribeckCurveCostTest : public testing::TestWithParam<double> {};

TEST_P(StribeckCurveCostTest, JacobianMatchesCentralDifferences) {
  const JointStribeck truth{0.8, 1.3, 0.06, 1.7, 0.4, 0.02, 0.01};
  const CurveSamples s = sample_curve(truth, 200, 3);
  const StribeckCurveCost cost(s.dq, s.abs_gravity, s.friction, GetParam());
  const int m = cost.num_residuals();
  auto residuals_at = [&](const double* x) {
    Eigen::VectorXd r(m);
    cost.Evaluate(&x, r.data(), nullptr);
    return r;
  };
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    double x[7] = {0.2 + unit(rng), 2.0 * unit(rng),  0.01 + 0.3 * unit(rng), 0.5 + 2.5 * unit(rng),
                   unit(rng),       0.05 * unit(rng), 0.05 * unit(rng)};
    Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor> jacobian(m, 7);
    Eigen::VectorXd r(m);
    const double* parameters = x;
    double* jacobians[] = {jacobian.data()};
    ASSERT_TRUE(cost.Evaluate(&parameters, r.data(), jacobians));
    EXPECT_LT((r - residuals_at(x)).cwiseAbs().maxCoeff(), 1e-15);
    for (int i = 0; i < 7; ++i) {
      const double h = 1e-6 * std::max(1.0, std::abs(x[i]));
      double plus[7], minus[7];
      std::copy(x, x + 7, plus);
      std::copy(x, x + 7, minus);
      plus[i] += h;
      minus[i] -= h;
      const Eigen::VectorXd numeric = (residuals_at(plus) - residuals_at(minus)) / (2 * h);
      EXPECT_LT((jacobian.col(i) - numeric).cwiseAbs().maxCoeff(), 1e-6)
          << "parameter " << i << ", trial " << trial;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(PlainAndCauchy, StribeckCurveCostTest, testing::Values(0.0, 0.3));

TEST(StribeckCurveCost, CauchyResidualsSumToTheCauchyLoss) {
  const JointStribeck truth{0.8, 1.3, 0.06, 1.7, 0.4, 0.02, 0.01};
  const CurveSamples s = sample_curve(truth, 50, 4);
  const double x[7] = {0.5, 1.0, 0.1, 1.2, 0.3, 0.0, 0.0}, c = 0.2;
  const double* parameters = x;
  Eigen::VectorXd plain(50), robust(50);
  StribeckCurveCost(s.dq, s.abs_gravity, s.friction).Evaluate(&parameters, plain.data(), nullptr);
  StribeckCurveCost(s.dq, s.abs_gravity, s.friction, c)
      .Evaluate(&parameters, robust.data(), nullptr);
  for (int k = 0; k < 50; ++k) {
    EXPECT_NEAR(robust[k] * robust[k], c * c * std::log(1.0 + plain[k] * plain[k] / (c * c)),
                1e-12);
    EXPECT_EQ(std::signbit(robust[k]), std::signbit(plain[k]));
  }
}

TEST(StribeckFit, CauchyLossFollowsTheCurveThroughOutliers) {
  // Every tenth sample 2 N·m off (an onset whose friction is not yet the sliding curve's): the
  // Cauchy fit keeps the curve's sliding level, plain least squares is pulled ≈ 0.2 N·m off.
  const JointStribeck truth{0.8, 1.3, 0.06, 1.7, 0.4, 0.0, 0.0};
  CurveSamples s = sample_curve(truth, 600, 9);
  for (int k = 0; k < 600; k += 10)
    s.friction[k] += std::copysign(2.0, s.dq[k]);
  JointStribeck start;
  start.coulomb = 0.6;
  start.viscous = 0.3;
  const StribeckFit plain = fit_stribeck(s.dq, s.abs_gravity, s.friction, start, false);
  const StribeckFit robust = fit_stribeck(s.dq, s.abs_gravity, s.friction, start, false, 0.1);
  EXPECT_NEAR(robust.curve.coulomb, truth.coulomb, 0.02);
  EXPECT_NEAR(robust.curve.static_friction, truth.static_friction, 0.05);
  EXPECT_GT(std::abs(plain.curve.coulomb - truth.coulomb), 0.1);
}

TEST(StribeckFit, RecoversAKnownCurveWithLoadDependence) {
  const JointStribeck truth{0.8, 1.3, 0.06, 1.7, 0.4, 0.02, 0.01};
  const CurveSamples s = sample_curve(truth, 600, 5);
  JointStribeck start;
  start.coulomb = 0.6;
  start.viscous = 0.3;
  const StribeckFit fit = fit_stribeck(s.dq, s.abs_gravity, s.friction, start, true);
  EXPECT_NEAR(fit.curve.coulomb, truth.coulomb, 1e-6);
  EXPECT_NEAR(fit.curve.static_friction, truth.static_friction, 1e-6);
  EXPECT_NEAR(fit.curve.stribeck_velocity, truth.stribeck_velocity, 1e-6);
  EXPECT_NEAR(fit.curve.stribeck_exponent, truth.stribeck_exponent, 1e-5);
  EXPECT_NEAR(fit.curve.viscous, truth.viscous, 1e-6);
  EXPECT_NEAR(fit.curve.load_coulomb, truth.load_coulomb, 1e-7);
  EXPECT_NEAR(fit.curve.load_viscous, truth.load_viscous, 1e-7);
  EXPECT_TRUE(fit.at_bound.empty());
}

TEST(StribeckFit, NamesABindingBoundAndHoldsTheLoadTermsAtZero) {
  // A step from static to sliding friction at 0.05 rad/s (δ = 20, beyond the curve's δ ≤ 4): the
  // fit ends on δ's upper bound and says so; without fit_load the load terms stay at zero
  // whatever the start.
  const JointStribeck truth{0.5, 1.0, 0.05, 20.0, 0.2, 0.0, 0.0};
  const CurveSamples s = sample_curve(truth, 400, 7);
  JointStribeck start;
  start.coulomb = 0.5;
  start.viscous = 0.2;
  start.load_coulomb = 0.3;  // ignored without fit_load
  const StribeckFit fit = fit_stribeck(s.dq, s.abs_gravity, s.friction, start, false);
  EXPECT_EQ(fit.curve.load_coulomb, 0.0);
  EXPECT_EQ(fit.curve.load_viscous, 0.0);
  EXPECT_EQ(fit.curve.stribeck_exponent, 4.0);
  ASSERT_FALSE(fit.at_bound.empty());
  EXPECT_NE(fit.at_bound.front().find("δ at its upper bound 4"), std::string::npos)
      << fit.at_bound.front();
}

}  // namespace
}  // namespace tpf::offline
