// Identities of the Stribeck + viscous friction model and its smooth and load-dependent forms.
#include "tpf/friction/stribeck.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "support/allocation_counter.hpp"

namespace {

using Vec = tpf::JointVector<double, 4>;

tpf::StribeckParameters<double, 4> stribeck_reference() {
  tpf::StribeckParameters<double, 4> p;
  p.coulomb << 1.3, 1.6, 0.9, 0.6;
  p.static_friction << 2.1, 2.5, 1.45, 1.0;
  p.stribeck_velocity << 0.04, 0.035, 0.05, 0.06;
  p.stribeck_exponent << 1.5, 1.5, 1.2, 2.0;
  p.viscous << 2.6, 3.2, 1.6, 1.1;
  p.load_coulomb << 0.0, 0.045, 0.06, 0.08;
  p.load_viscous << 0.0, 0.06, 0.08, 0.1;
  return p;
}

TEST(Stribeck, ReferenceValue) {
  const auto p = stribeck_reference();
  // Joint 2 at q̇ = 0.05 rad/s, |G| = 8 N·m, by hand:
  // [1.6 + 0.045·8 + 0.9·exp(−(0.05/0.035)^1.5)] + (3.2 + 0.06·8)·0.05
  const double expected = 1.6 + 0.36 + 0.9 * std::exp(-std::pow(0.05 / 0.035, 1.5)) + 3.68 * 0.05;
  EXPECT_NEAR(tpf::stribeck_friction(p, 1, 0.05, 8.0), expected, 1e-14);
}

TEST(Stribeck, OddSymmetry) {
  const auto p = stribeck_reference();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> v(-2.0, 2.0), g(0.0, 15.0);
  for (int k = 0; k < 200; ++k) {
    const Vec dq = Vec::NullaryExpr([&] { return v(rng); });
    const Vec ag = Vec::NullaryExpr([&] { return g(rng); });
    EXPECT_TRUE(
        tpf::stribeck_friction(p, dq, ag).isApprox(-tpf::stribeck_friction(p, Vec(-dq), ag)));
    EXPECT_TRUE(tpf::smooth_stribeck_friction(p, dq, ag).isApprox(
        -tpf::smooth_stribeck_friction(p, Vec(-dq), ag)));
  }
}

TEST(Stribeck, LimitsAtZeroAndInfinity) {
  const auto p = stribeck_reference();
  const double tiny = 1e-12, g = 5.0;
  for (int j = 0; j < 4; ++j) {
    // q̇ → 0⁺: static friction plus the load term; exactly 0 at q̇ = 0.
    EXPECT_NEAR(tpf::stribeck_friction(p, j, tiny, g), p.static_friction[j] + p.load_coulomb[j] * g,
                1e-9);
    EXPECT_EQ(tpf::stribeck_friction(p, j, 0.0, g), 0.0);
    // q̇ → ∞: Coulomb + viscous asymptote.
    const double v = 200.0 * p.stribeck_velocity[j];
    EXPECT_NEAR(tpf::stribeck_friction(p, j, v, g),
                p.coulomb[j] + p.load_coulomb[j] * g + (p.viscous[j] + p.load_viscous[j] * g) * v,
                1e-12);
  }
}

TEST(Stribeck, NoLoadEqualsZeroGravity) {
  const auto p = stribeck_reference();
  const Vec dq(0.3, -0.01, 0.002, -1.5);
  EXPECT_TRUE(
      tpf::stribeck_friction(p, dq).isApprox(tpf::stribeck_friction(p, dq, Vec(Vec::Zero()))));
}

TEST(Stribeck, LoadTermsAreLinearInTheirCoefficients) {
  auto p = stribeck_reference();
  const Vec dq(0.3, -0.2, 0.1, -0.05), ag(0.0, 7.0, 3.0, 1.0);
  const Vec with = tpf::stribeck_friction(p, dq, ag);
  p.load_coulomb.setZero();
  p.load_viscous.setZero();
  const Vec without = tpf::stribeck_friction(p, dq, ag);
  const Vec a_c = stribeck_reference().load_coulomb, a_v = stribeck_reference().load_viscous;
  const Vec expected =
      (a_c.cwiseProduct(ag)).cwiseProduct(dq.cwiseSign()) + a_v.cwiseProduct(ag).cwiseProduct(dq);
  EXPECT_TRUE((with - without).isApprox(expected, 1e-12));
}

TEST(Stribeck, SmoothFormIsContinuousAndConverges) {
  const auto p = stribeck_reference();
  const Vec ag = Vec::Constant(2.0);
  const double eps = 0.01;
  // Continuity at 0: values from both sides approach 0 linearly with slope g(0)/ε + b.
  for (double h : {1e-6, 1e-8}) {
    const Vec plus = tpf::smooth_stribeck_friction(p, Vec(Vec::Constant(h)), ag, eps);
    const Vec minus = tpf::smooth_stribeck_friction(p, Vec(Vec::Constant(-h)), ag, eps);
    EXPECT_LT((plus - minus).cwiseAbs().maxCoeff(), 1e3 * h);
  }
  EXPECT_TRUE(tpf::smooth_stribeck_friction(p, Vec(Vec::Zero()), ag, eps).isZero(0.0));
  // Far from 0 it equals the sharp form within tanh(v/ε) ≥ 1 − 2e-9 (v = 10ε... use 20ε).
  const Vec dq = Vec::Constant(0.2);
  const Vec sharp = tpf::stribeck_friction(p, dq, ag);
  const Vec smooth = tpf::smooth_stribeck_friction(p, dq, ag, eps);
  EXPECT_LT((sharp - smooth).cwiseAbs().maxCoeff(), 1e-7);
  // Derivative at 0 by central difference: g(0)/ε + b (with load terms).
  const double h = 1e-7;
  for (int j = 0; j < 4; ++j) {
    Vec a = Vec::Zero(), b = Vec::Zero();
    a[j] = h;
    b[j] = -h;
    const double slope = (tpf::smooth_stribeck_friction(p, a, ag, eps)[j] -
                          tpf::smooth_stribeck_friction(p, b, ag, eps)[j]) /
                         (2 * h);
    const double expected = (p.static_friction[j] + p.load_coulomb[j] * 2.0) / eps + p.viscous[j] +
                            p.load_viscous[j] * 2.0;
    EXPECT_NEAR(slope, expected, 1e-4 * expected);
  }
}

TEST(Stribeck, EvaluationAllocatesNothing) {
  const auto p = stribeck_reference();
  const Vec dq(0.3, -0.2, 0.1, -0.05), ag(0.0, 7.0, 3.0, 1.0);
  Vec sum = Vec::Zero();
  tpf::test::AllocationCounter counter;
  for (int k = 0; k < 100; ++k) {
    sum += tpf::stribeck_friction(p, dq, ag);
    sum += tpf::smooth_stribeck_friction(p, dq, ag);
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(sum.allFinite());
}

}  // namespace
