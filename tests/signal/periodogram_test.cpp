// The real-valued frequency fit diagnose and the measured loop name a ripple with, and the
// range of motion that decides whether its period is in view.
#include "offline/signal/periodogram.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

namespace tpf::offline {
namespace {

TEST(Periodogram, FindsTheOutputRippleAndItsPeriodsInTheRangeOfMotion) {
  const int n = 4000;
  Eigen::VectorXd q(n), output(n);
  for (int k = 0; k < n; ++k) {
    q[k] = -1.5 + 3.0 * k / (n - 1.0);
    output[k] = 0.3 * std::sin(7 * q[k] + 0.4) + 0.1 * q[k] + 0.05 * std::sin(11 * q[k]);
  }
  const OutputRipple ripple = output_ripple(q, output);
  EXPECT_NEAR(ripple.range, 0.98 * 3.0, 1e-3);  // the central 98 %
  EXPECT_NEAR(ripple.cycles, 7.0, 0.05);
  EXPECT_NEAR(ripple.periods, ripple.cycles * ripple.range / (2 * M_PI), 1e-12);
  // Over 0.05 rad not one period of 64/rev fits: nothing is searched.
  const Eigen::VectorXd still = 0.05 / 3.0 * q;
  EXPECT_EQ(output_ripple(still, output).cycles, 0.0);
  EXPECT_EQ(output_ripple(Eigen::VectorXd(), Eigen::VectorXd()).cycles, 0.0);  // no data
}

TEST(Periodogram, ThePeriodMustFitInTheRangeOfMotion) {
  EXPECT_EQ(shortest_fitting_cycles(2 * M_PI / 5), 5);  // one period of 5/rev fits exactly
  EXPECT_EQ(shortest_fitting_cycles(0.38), 17);         // 2π/0.38 = 16.5
  EXPECT_EQ(shortest_fitting_cycles(10.0), 3);          // never below 3
  EXPECT_EQ(shortest_fitting_cycles(0.0), 1000000);     // no motion: no ripple fits
}

/// q swept back and forth over [centre − half, centre + half] at uneven speed, and the residual
/// `ripple`(q) + an offset + a slope + white noise of std 0.05.
template <typename Ripple>
void planted(double centre, double half, Ripple ripple, Eigen::VectorXd& q, Eigen::VectorXd& r) {
  const int n = 20000;
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.05);
  q.resize(n);
  r.resize(n);
  for (int k = 0; k < n; ++k) {
    const double phase = 2 * M_PI * 9.3 * k / n;
    q[k] = centre + half * std::sin(phase + 0.3 * std::sin(3 * phase));
    r[k] = ripple(q[k]) + 0.4 - 0.3 * q[k] + noise(random);
  }
}

TEST(Periodogram, FitsTheFrequencyAsARealNumber) {
  // 30.65 periods/rev over 3 rad (14.6 periods), beside an offset and a slope (the integer
  // periodogram, which does not fit them, says 4).
  Eigen::VectorXd q, r;
  planted(
      0.2, 1.5, [](double x) { return 0.1 * std::sin(30.65 * x + 0.4); }, q, r);
  const double f = fitted_cycles(q, r, 3, 64, 1.0);
  std::printf("  fitted %.4f periods/rev (planted 30.65)\n", f);
  EXPECT_LT(std::abs(f - 30.65) / 30.65, 0.03) << f;
  EXPECT_NEAR(f, 30.65, 0.15);
  EXPECT_GT(explained_share(q, r, f, 1.0), 0.6);  // 2/3: noise 0.05, ripple of RMS 0.07
}

TEST(Periodogram, FitsTheMotorSideFrequency) {
  // 2 periods per motor revolution through a gear ratio of 121 over 0.8 rad of q (31 periods of
  // the motor angle), beside an output ripple of 9 periods/rev.
  Eigen::VectorXd q, r;
  planted(
      -0.4, 0.4,
      [](double x) { return 0.08 * std::sin(2.0 * 121 * x + 0.7) + 0.1 * std::sin(9 * x); }, q, r);
  const double f = fitted_cycles(q, r, 0.5, 4.5, 121);
  std::printf("  fitted %.4f periods/motor rev (planted 2)\n", f);
  EXPECT_LT(std::abs(f - 2.0) / 2.0, 0.03) << f;
  EXPECT_NEAR(f, 2.0, 0.01);
}

TEST(Periodogram, FitsAFrequencyWithLittleMoreThanOnePeriodInView) {
  // 24 periods/rev over 0.35 rad: 1.3 periods, beside an offset and a slope.
  Eigen::VectorXd q, r;
  planted(
      0.5, 0.175, [](double x) { return 0.2 * std::sin(24 * x + 1.1); }, q, r);
  const double f = fitted_cycles(q, r, std::max(3.0, M_PI / 0.35), 64, 1.0);
  std::printf("  fitted %.4f periods/rev (planted 24)\n", f);
  EXPECT_LT(std::abs(f - 24) / 24, 0.03) << f;
}

TEST(Periodogram, NoMotionNoFrequency) {
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(50, 0.3), r = Eigen::VectorXd::Ones(50);
  EXPECT_EQ(fitted_cycles(q, r, 3, 64, 1.0), 0.0);
  EXPECT_EQ(fitted_cycles(Eigen::VectorXd(), Eigen::VectorXd(), 3, 64, 1.0), 0.0);
}

}  // namespace
}  // namespace tpf::offline
