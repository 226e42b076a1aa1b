#include "offline/regimes/regime.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "offline/regimes/regime_stats.hpp"
#include "support/constants.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

using tpf::test::kNaN;
constexpr Regime S = Regime::Static;
constexpr Regime T = Regime::StaticToKinetic;
constexpr Regime M = Regime::Moving;
constexpr Regime I = Regime::Invalid;

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index k = 0;
  for (const double x : values)
    v[k++] = x;
  return v;
}

/// t = 0, 0.01, 0.02, ... (100 Hz) for hand-made sequences.
Eigen::VectorXd steps(Eigen::Index n) {
  return Eigen::VectorXd::LinSpaced(n, 0.0, 0.01 * (n - 1));
}

TEST(LabelRegimes, FallbackWindowAfterAStaticStretch) {
  RegimeOptions options;
  options.fallback_transition_s = 0.035;  // samples at +0, +0.01, +0.02, +0.03 after the crossing
  const Eigen::VectorXd dq = vec({0, 5e-5, -9e-5, 1e-3, 2e-3, 3e-3, 4e-3, 5e-3, 6e-3, 0, 0});
  const auto labels = label_regimes(steps(11), dq, options);
  EXPECT_EQ(labels, (std::vector<Regime>{S, S, S, T, T, T, T, M, M, S, S}));
}

TEST(LabelRegimes, ThresholdIsStrictAndSignFree) {
  RegimeOptions options;
  options.static_velocity = 1e-4;
  const auto labels = label_regimes(steps(4), vec({-0.99e-4, -1e-4, 0, 1e-4}), options);
  EXPECT_EQ(labels, (std::vector<Regime>{S, T, S, T}));
}

TEST(LabelRegimes, MotionAtTheStartIsMovingAndNaNIsInvalid) {
  const auto labels = label_regimes(steps(6), vec({1, 1, kNaN, 0, 1, 1}), {});
  // After the NaN, sample 3 is static, so 4 starts a transition; 70 ms fallback covers 4 and 5.
  EXPECT_EQ(labels, (std::vector<Regime>{M, M, I, S, T, T}));
}

TEST(LabelRegimes, ResidualsMeetingEndTheWindow) {
  const Eigen::VectorXd dq = vec({0, 0, 1, 1, 1, 1, 1, 1});
  const Eigen::VectorXd r_nom = vec({5, 5, 9, 8, 7, 6, 5, 4});
  // Difference nominal − compensated: 4, 4, 6, 4, 2, 0.5, 0.1, 0: meets (≤ 0.2) at sample 6.
  const Eigen::VectorXd r_comp = vec({1, 1, 3, 4, 5, 5.5, 4.9, 4});
  const auto labels = label_regimes(steps(8), dq, {}, &r_nom, &r_comp, 0.2);
  EXPECT_EQ(labels, (std::vector<Regime>{S, S, T, T, T, T, M, M}));
  // A sign change of the difference also ends it: −1 at sample 4.
  const Eigen::VectorXd r_cross = vec({1, 1, 3, 4, 8, 5, 5, 5});
  EXPECT_EQ(label_regimes(steps(8), dq, {}, &r_nom, &r_cross, 0.0),
            (std::vector<Regime>{S, S, T, T, M, M, M, M}));
}

TEST(LabelRegimes, WindowNeverExceedsTheMaximum) {
  RegimeOptions options;
  options.max_transition_s = 0.025;
  const Eigen::VectorXd dq = vec({0, 1, 1, 1, 1, 1});
  const Eigen::VectorXd r_nom = Eigen::VectorXd::Constant(6, 10.0);
  const Eigen::VectorXd r_comp = Eigen::VectorXd::Zero(6);  // never meet
  EXPECT_EQ(label_regimes(steps(6), dq, options, &r_nom, &r_comp, 0.1),
            (std::vector<Regime>{S, T, T, T, M, M}));
}

TEST(LabelRegimes, NoTransitionAcrossAGap) {
  Eigen::VectorXd t = steps(8);
  t.tail(5).array() += 0.1;  // gap between samples 2 and 3
  const Eigen::VectorXd dq = vec({0, 0, 0, 1, 1, 0, 1, 1});
  EXPECT_EQ(label_regimes(t, dq, {}), (std::vector<Regime>{S, S, S, M, M, S, T, T}));
  // A window that started before a gap ends at it.
  const Eigen::VectorXd dq2 = vec({0, 0, 1, 1, 1, 1, 1, 1});
  EXPECT_EQ(label_regimes(t, dq2, {}), (std::vector<Regime>{S, S, T, M, M, M, M, M}));
}

TEST(LabelRegimes, SizeMismatchIsAnError) {
  EXPECT_THROW(label_regimes(steps(3), vec({0, 1}), {}), Error);
  const Eigen::VectorXd r = vec({1});
  EXPECT_THROW(label_regimes(steps(2), vec({0, 1}), {}, &r, &r), Error);
}

TEST(RegimeStats, RmseAndStdPerRegimeSkippingNaN) {
  const std::vector<Regime> labels{S, S, S, T, T, M, M, M, I};
  const Eigen::VectorXd r = vec({1, -1, 3, 2, 2, kNaN, 4, -4, 100});
  const RegimeStats stats = regime_stats(r, labels);
  EXPECT_EQ(stats[S].count, 3u);
  EXPECT_DOUBLE_EQ(stats[S].mean, 1.0);
  EXPECT_DOUBLE_EQ(stats[S].rmse, std::sqrt(11.0 / 3.0));
  EXPECT_DOUBLE_EQ(stats[S].std, std::sqrt(8.0 / 3.0));
  EXPECT_DOUBLE_EQ(stats[T].rmse, 2.0);
  EXPECT_DOUBLE_EQ(stats[T].std, 0.0);
  EXPECT_EQ(stats[M].count, 2u);
  EXPECT_DOUBLE_EQ(stats[M].rmse, 4.0);
  EXPECT_DOUBLE_EQ(stats[M].std, 4.0);
  EXPECT_EQ(stats[I].count, 1u);
  EXPECT_EQ(stats.valid.count, 7u);
  EXPECT_DOUBLE_EQ(stats.valid.rmse, std::sqrt((1 + 1 + 9 + 4 + 4 + 16 + 16) / 7.0));
  const RegimeStats empty = regime_stats(vec({kNaN}), {S});
  EXPECT_EQ(empty[S].count, 0u);
  EXPECT_TRUE(std::isnan(empty[S].rmse));
  EXPECT_THROW(regime_stats(vec({1, 2}), {S}), Error);
}

TEST(RegimeStats, PercentChange) {
  EXPECT_NEAR(percent_change(280.17, 31.96), -88.5926, 1e-4);
  EXPECT_TRUE(std::isnan(percent_change(0.0, 1.0)));
  EXPECT_TRUE(std::isnan(percent_change(kNaN, 1.0)));
  EXPECT_EQ(regime_name(Regime::StaticToKinetic), "static-to-kinetic");
}

}  // namespace
}  // namespace tpf::offline
