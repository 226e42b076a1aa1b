// The pad low-pass: coefficient, step response, gain at the cut-off, noise gain.
#include "tpf/skin/pad_low_pass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>

#include "support/constants.hpp"

namespace {

using tpf::test::kPeriod;
constexpr double kPi = std::numbers::pi;

TEST(PadLowPass, CoefficientIsTheExactZeroOrderHoldDiscretisation) {
  EXPECT_NEAR(tpf::low_pass_coefficient(40.0, kPeriod), 1.0 - std::exp(-2 * kPi * 40 * kPeriod),
              1e-15);
  EXPECT_NEAR(tpf::low_pass_coefficient(40.0, kPeriod), 0.46651, 1e-5);
  // Two half periods equal one full period: the cut-off does not depend on the sample rate.
  const double half = tpf::low_pass_coefficient(40.0, kPeriod / 2);
  EXPECT_NEAR(1 - (1 - half) * (1 - half), tpf::low_pass_coefficient(40.0, kPeriod), 1e-15);
}

TEST(PadLowPass, StepResponseFollowsTheContinuousFirstOrderLag) {
  tpf::PadLowPass<double> f(40.0);
  f.reset(0.0);
  const double tau = 1.0 / (2 * kPi * 40.0);
  for (int k = 1; k <= 40; ++k) {
    const double y = f.update(1.0, kPeriod);
    EXPECT_NEAR(y, 1.0 - std::exp(-k * kPeriod / tau), 1e-12) << k;
  }
}

TEST(PadLowPass, DroppedCycleKeepsTheTimeConstant) {
  tpf::PadLowPass<double> a(40.0), b(40.0);
  a.reset(0.0);
  b.reset(0.0);
  a.update(1.0, kPeriod);
  a.update(1.0, kPeriod);
  b.update(1.0, 2 * kPeriod);  // one sample lost, input held
  EXPECT_NEAR(a.value(), b.value(), 1e-12);
}

TEST(PadLowPass, GainAtCutoffIsMinusThreeDecibels) {
  tpf::PadLowPass<double> f(40.0);
  f.reset(0.0);
  const double w = 2 * kPi * 40.0;
  double peak = 0;
  for (int k = 0; k < 4000; ++k) {
    const double y = f.update(std::sin(w * k * kPeriod), kPeriod);
    if (k > 2000) peak = std::max(peak, std::abs(y));
  }
  // Discrete response α / (1 − (1 − α)e^{−jωh}) at ω = 2π·40, sampled peaks slightly below it.
  const double alpha = tpf::low_pass_coefficient(40.0, kPeriod);
  const double exact =
      std::abs(alpha / (1.0 - (1.0 - alpha) * std::exp(std::complex<double>(0, -w * kPeriod))));
  EXPECT_NEAR(exact, 1 / std::sqrt(2.0), 0.03);  // ZOH discretisation at f/fs = 0.1
  EXPECT_LE(peak, exact + 1e-9);
  EXPECT_GE(peak, exact * std::cos(w * kPeriod / 2));  // sampling can miss the peak by ≤ h/2
}

TEST(PadLowPass, WhiteNoiseGainMatchesTheFormula) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  tpf::PadLowPass<double> f(40.0);
  f.reset(0.0);
  double sum2 = 0;
  const int n = 200000;
  for (int k = 0; k < n; ++k) {
    const double y = f.update(noise(rng), kPeriod);
    sum2 += y * y;
  }
  const double expected = tpf::low_pass_noise_gain(tpf::low_pass_coefficient(40.0, kPeriod));
  EXPECT_NEAR(std::sqrt(sum2 / n), expected, 0.02 * expected);
}

}  // namespace
