#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "offline/signal/acceleration.hpp"
#include "offline/signal/butterworth.hpp"
#include "offline/signal/segments.hpp"
#include "support/constants.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

constexpr double kPi = std::numbers::pi;
using tpf::test::kNaN;
constexpr double kRate = 400.0;

Eigen::VectorXd time_axis(Eigen::Index n) {
  return Eigen::VectorXd::LinSpaced(n, 0.0, static_cast<double>(n - 1) / kRate);
}

TEST(Butterworth2, CoefficientsMatchTheAnalogPrototype) {
  const Butterworth2 f = Butterworth2::low_pass(20.0, kRate);
  // Reference values from the bilinear transform with pre-warping (scipy.signal.butter(2, 0.1)).
  EXPECT_NEAR(f.b0, 0.020083365564211, 1e-12);
  EXPECT_NEAR(f.b1, 0.040166731128423, 1e-12);
  EXPECT_NEAR(f.a1, -1.561018075800718, 1e-12);
  EXPECT_NEAR(f.a2, 0.641351538057563, 1e-12);
  // |H| at the cutoff is 1/√2: evaluate H(e^{jω}) at ω = 2π·20/400.
  const std::complex<double> z = std::polar(1.0, 2 * kPi * 20.0 / kRate);
  const std::complex<double> h =
      (f.b0 + f.b1 / z + f.b2 / (z * z)) / (1.0 + f.a1 / z + f.a2 / (z * z));
  EXPECT_NEAR(std::abs(h), 1 / std::sqrt(2.0), 1e-12);
  EXPECT_THROW(Butterworth2::low_pass(200.0, kRate), Error);
  EXPECT_THROW(Butterworth2::low_pass(0.0, kRate), Error);
}

TEST(Filtfilt, ConstantAndRampPassUnchanged) {
  const Butterworth2 f = Butterworth2::low_pass(10.0, kRate);
  const Eigen::VectorXd c = Eigen::VectorXd::Constant(50, 3.5);
  EXPECT_LT((filtfilt(f, c, 40.0) - c).cwiseAbs().maxCoeff(), 1e-12);
  // Odd reflection keeps a ramp a ramp at the edges; only the start-up transient of the padding
  // (steady state assumed for a constant) leaves a trace.
  const Eigen::VectorXd ramp = Eigen::VectorXd::LinSpaced(300, -1.0, 2.0);
  EXPECT_LT((filtfilt(f, ramp, 40.0) - ramp).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(Filtfilt, StepResponseIsSymmetric) {
  const Butterworth2 f = Butterworth2::low_pass(15.0, kRate);
  Eigen::VectorXd step = Eigen::VectorXd::Zero(400);
  step.tail(200).setOnes();
  const Eigen::VectorXd y = filtfilt(f, step, kRate / 15.0);
  // Zero phase: y[200 + m] − ½ = −(y[199 − m] − ½), and the edge moves (no lag).
  for (int m = 0; m < 100; ++m)
    EXPECT_NEAR(y[200 + m] + y[199 - m], 1.0, 1e-9) << m;
  EXPECT_GT(y[200], 0.5);
  EXPECT_LT(y[199], 0.5);
  EXPECT_GT(y[150] - 0.0, -0.03);  // small symmetric ringing only
}

TEST(Filtfilt, NoPhaseLagCrossCorrelationPeaksAtZero) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  const Eigen::Index n = 4000;
  Eigen::VectorXd x(n);
  for (Eigen::Index k = 0; k < n; ++k)
    x[k] = noise(rng);
  const Eigen::VectorXd y = filtfilt(Butterworth2::low_pass(5.0, kRate), x, kRate / 5.0);
  int best_lag = 99;
  double best = -1e300;
  for (int lag = -20; lag <= 20; ++lag) {
    double sum = 0;
    for (Eigen::Index k = 50; k < n - 50; ++k)
      sum += x[k] * y[k + lag];
    if (sum > best) best = sum, best_lag = lag;
  }
  EXPECT_EQ(best_lag, 0);
}

TEST(DeriveAcceleration, RecoversASineDerivative) {
  // dq = A·ω·cos(ωt) → ddq = −A·ω²·sin(ωt); 1 Hz motion, 20 Hz cutoff, 400 Hz sampling.
  const Eigen::VectorXd t = time_axis(2000);
  const double w = 2 * kPi * 1.0, a = 0.5;
  const Eigen::VectorXd dq = (a * w) * (w * t).array().cos().matrix();
  const Eigen::VectorXd ddq = derive_acceleration(t, dq, 20.0);
  const double peak = a * w * w;
  EXPECT_TRUE(std::isnan(ddq[0]));
  EXPECT_TRUE(std::isnan(ddq[1999]));
  double worst_interior = 0, worst_all = 0;
  for (Eigen::Index k = 1; k < 1999; ++k) {
    const double error = std::abs(ddq[k] + peak * std::sin(w * t[k]));
    worst_all = std::max(worst_all, error);
    if (k > 40 && k < 1960) worst_interior = std::max(worst_interior, error);
  }
  EXPECT_LT(worst_interior, 1e-4 * peak);  // stated tolerance: 0.01 % of the peak inside
  EXPECT_LT(worst_all, 5e-2 * peak);       // and 5 % at the segment edges
}

TEST(DeriveAcceleration, NeverDifferentiatesAcrossGapsOrNaN) {
  Eigen::VectorXd t = time_axis(600);
  t.tail(300).array() += 0.05;  // 20 dropped cycles between samples 299 and 300
  Eigen::VectorXd dq = (2 * kPi * 2 * t).array().sin().matrix();
  dq[450] = kNaN;
  const Eigen::VectorXd ddq = derive_acceleration(t, dq, 25.0);
  for (Eigen::Index k : {0, 299, 300, 449, 450, 451, 599})
    EXPECT_TRUE(std::isnan(ddq[k])) << k;
  EXPECT_EQ((ddq.array().isNaN()).count(), 7);
  // Each segment is processed on its own: same values as when given alone.
  const Eigen::VectorXd alone =
      derive_acceleration(t.segment(300, 150), dq.segment(300, 150), 25.0);
  for (Eigen::Index k = 1; k < 149; ++k)
    EXPECT_NEAR(ddq[300 + k], alone[k], 1e-9) << k;
  // A slope step of the velocity in the other segment does not leak across the gap.
  Eigen::VectorXd dq2 = dq;
  dq2.head(300).array() += 100.0;
  const Eigen::VectorXd ddq2 = derive_acceleration(t, dq2, 25.0);
  for (Eigen::Index k = 301; k < 449; ++k)
    EXPECT_EQ(ddq2[k], ddq[k]);
}

TEST(DeriveAcceleration, GivenMedianStepGivesTheSameBits) {
  // Jittered time with a gap and NaNs: the overloads that take t's median step (computed once by
  // a caller filtering several signals) return exactly what the ones computing it return.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> jitter(-2e-5, 2e-5);
  const int n = 5000;
  Eigen::VectorXd t(n), dq(n);
  for (int k = 0; k < n; ++k) {
    t[k] = k / kRate + jitter(rng) + (k >= 3000 ? 0.1 : 0.0);
    dq[k] = std::sin(2 * kPi * 0.7 * t[k]) + 0.01 * jitter(rng) * 1e5;
  }
  dq[100] = dq[2500] = kNaN;
  const double step = median_step(t);
  const Eigen::VectorXd a = derive_acceleration(t, dq, 20.0);
  const Eigen::VectorXd b = derive_acceleration(t, dq, 20.0, step);
  const Eigen::VectorXd c = zero_phase_low_pass(t, dq, 20.0);
  const Eigen::VectorXd d = zero_phase_low_pass(t, dq, 20.0, step);
  for (int k = 0; k < n; ++k) {
    ASSERT_TRUE(a[k] == b[k] || (std::isnan(a[k]) && std::isnan(b[k]))) << k;
    ASSERT_TRUE(c[k] == d[k] || (std::isnan(c[k]) && std::isnan(d[k]))) << k;
  }
  const auto segments = contiguous_segments(t, dq, 1.5);
  const auto given = contiguous_segments(t, dq, 1.5, step);
  ASSERT_EQ(segments.size(), given.size());
  EXPECT_EQ(segments.size(), 4u);
  for (std::size_t i = 0; i < given.size(); ++i) {
    EXPECT_EQ(segments[i].begin, given[i].begin);
    EXPECT_EQ(segments[i].end, given[i].end);
  }
}

TEST(Segments, SplitAtGapsAndNaN) {
  Eigen::VectorXd t(8);
  t << 0, 1, 2, 3, 5, 6, 7, 8;
  Eigen::VectorXd x = Eigen::VectorXd::Ones(8);
  x[6] = kNaN;
  const auto segments = contiguous_segments(t, x);
  ASSERT_EQ(segments.size(), 3u);
  EXPECT_EQ(segments[0].begin, 0);
  EXPECT_EQ(segments[0].end, 4);
  EXPECT_EQ(segments[1].begin, 4);
  EXPECT_EQ(segments[1].end, 6);
  EXPECT_EQ(segments[2].begin, 7);
  EXPECT_EQ(segments[2].end, 8);
  EXPECT_DOUBLE_EQ(median_step(t), 1.0);
  EXPECT_THROW(contiguous_segments(t, Eigen::VectorXd::Ones(3)), Error);
}

TEST(ZeroPhaseLowPass, KeepsNaNAndAttenuatesNoise) {
  const Eigen::VectorXd t = time_axis(1000);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.1);
  Eigen::VectorXd x(1000);
  for (Eigen::Index k = 0; k < 1000; ++k)
    x[k] = std::sin(2 * kPi * t[k]) + noise(rng);
  x[500] = kNaN;
  const Eigen::VectorXd y = zero_phase_low_pass(t, x, 10.0);
  EXPECT_TRUE(std::isnan(y[500]));
  double error = 0;
  for (Eigen::Index k = 50; k < 450; ++k)
    error = std::max(error, std::abs(y[k] - std::sin(2 * kPi * t[k])));
  EXPECT_LT(error, 0.06);  // noise σ 0.1 → about 0.1·√(2·10·0.85/400) ≈ 0.02 σ after filtering
}

}  // namespace
}  // namespace tpf::offline
