// The delay candidate's lag search (search_effort_lag) on samples with a known lag: two joints
// whose effort is their prediction delayed by 37 ms plus noise, sampled at 1 kHz with a gap in t.
// The lag is found to the sample, the column times −lag gives the delayed prediction (the column
// is the difference quotient over the lag, not a derivative: exact for any lag), and samples
// whose lagged time falls in the gap or before the start have no column.
#include "offline/diagnose/effort_lag.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace tpf::test {
namespace {

/// A smooth prediction of two joints with steps in it (a reversal of friction every second).
double lag_test_prediction(int j, double t) {
  const double swing = std::sin(2 * M_PI * (0.7 + 0.3 * j) * t + j);
  return 3.0 * swing + (std::sin(2 * M_PI * 0.5 * t + j) > 0 ? 1.0 : -1.0);
}

struct LaggedSamples {
  offline::JointSamples s;
  Eigen::MatrixXd prediction, residual;
};

/// 1 kHz from 0 to 8 s with 0.5 s missing at 4 s; effort = prediction(t − lag) + noise.
LaggedSamples lagged_samples(double lag, double noise) {
  LaggedSamples out;
  offline::JointSamples& s = out.s;
  std::vector<double> times;
  for (int k = 0; k < 8000; ++k)
    if (k < 4000 || k >= 4500) times.push_back(k * 1e-3);
  const auto n = static_cast<Eigen::Index>(times.size());
  s.t = Eigen::Map<const Eigen::VectorXd>(times.data(), n);
  s.q = s.dq = s.ddq = s.effort = Eigen::MatrixXd::Zero(n, 2);
  s.regimes.assign(
      2, std::vector<offline::Regime>(static_cast<std::size_t>(n), offline::Regime::Moving));
  s.valid.assign(static_cast<std::size_t>(n), 1);
  s.heldout.assign(static_cast<std::size_t>(n), 0);
  out.prediction.resize(n, 2);
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, noise);
  for (Eigen::Index k = 0; k < n; ++k)
    for (int j = 0; j < 2; ++j) {
      out.prediction(k, j) = lag_test_prediction(j, s.t[k]);
      s.effort(k, j) = lag_test_prediction(j, s.t[k] - lag) + gauss(rng);
    }
  out.residual = s.effort - out.prediction;
  return out;
}

TEST(EffortLag, FindsTheLagToTheSampleAndItsColumnGivesTheDelayedPrediction) {
  const LaggedSamples x = lagged_samples(0.037, 0.02);
  const offline::EffortLag lag = offline::search_effort_lag(x.s, x.prediction, x.residual, 0.1);
  EXPECT_NEAR(lag.lag_s, 0.037, 1e-9);
  // Most of both joints' residual (all but the noise and the samples next to the gap and start).
  EXPECT_GT(lag.explained, 1.8);
  for (Eigen::Index k = 100; k < x.s.size(); k += 97) {
    if (x.s.t[k] >= 4.5 && x.s.t[k] < 4.537) continue;
    for (int j = 0; j < 2; ++j)
      EXPECT_NEAR(x.prediction(k, j) - 0.037 * lag.column(k, j),
                  lag_test_prediction(j, x.s.t[k] - 0.037), 1e-9)
          << "t " << x.s.t[k];
  }
}

TEST(EffortLag, AnEffortThatLeadsHasANegativeLag) {
  const LaggedSamples x = lagged_samples(-0.012, 0.02);
  EXPECT_NEAR(offline::search_effort_lag(x.s, x.prediction, x.residual, 0.1).lag_s, -0.012, 1e-9);
}

TEST(EffortLag, NoLagIsTakenAcrossAGapOrBeforeTheStart) {
  const LaggedSamples x = lagged_samples(0.037, 0.02);
  const offline::EffortLag lag = offline::search_effort_lag(x.s, x.prediction, x.residual, 0.1);
  for (Eigen::Index k = 0; k < x.s.size(); ++k) {
    const double t = x.s.t[k];
    if (t < 0.037 - 1e-9 || (t >= 4.5 && t < 4.537 - 1e-9)) {
      EXPECT_EQ(lag.column(k, 0), 0.0) << "t " << t;
      EXPECT_EQ(lag.column(k, 1), 0.0) << "t " << t;
    }
  }
}

}  // namespace
}  // namespace tpf::test
