// The persistence (k-in-a-row) test and the choice of k for a false-alarm rate.
#include "tpf/estimation/persistence_test.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace {

using tpf::persistence_for_false_alarm_rate;
using tpf::PersistenceTest;

Eigen::VectorXi bernoulli(double p, Eigen::Index n, unsigned seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution draw(p);
  Eigen::VectorXi e(n);
  for (Eigen::Index k = 0; k < n; ++k)
    e[k] = draw(rng) ? 1 : 0;
  return e;
}

/// Share of cycles on which a PersistenceTest of `samples` alarms over `exceeded`.
double alarm_share(const Eigen::VectorXi& exceeded, int samples) {
  PersistenceTest test(samples);
  long alarms = 0;
  for (Eigen::Index k = 0; k < exceeded.size(); ++k)
    alarms += test.update(exceeded[k] != 0) ? 1 : 0;
  return double(alarms) / double(exceeded.size());
}

TEST(PersistenceTest, AlarmsOnTheNthConsecutiveExceedanceAndClearsAtOnce) {
  PersistenceTest test(3);
  EXPECT_FALSE(test.update(true));
  EXPECT_FALSE(test.update(true));
  EXPECT_FALSE(test.update(false));  // a gap restarts the count
  EXPECT_FALSE(test.update(true));
  EXPECT_FALSE(test.update(true));
  EXPECT_TRUE(test.update(true));
  EXPECT_TRUE(test.update(true));  // stays on while exceeded
  EXPECT_FALSE(test.update(false));
  test.update(true);
  test.update(true);
  test.reset();
  EXPECT_FALSE(test.update(true));
  EXPECT_TRUE(PersistenceTest(1).update(true));  // 1: every exceedance
  EXPECT_EQ(PersistenceTest(0).required(), 1);
}

// White noise exceeds its band independently with probability p per cycle, so k in a row alarms
// with probability p^k: for p = 0.3 and a wanted rate of 1 %, k = 4 (0.81 %; k = 3 gives 2.7 %).
// On an independent noise-only sequence the chosen test alarms at that rate.
TEST(PersistenceTest, ChosenLengthMeetsTheFalseAlarmRateOnNoiseOnly) {
  const double p = 0.3, rate = 0.01;
  const Eigen::VectorXi calibration = bernoulli(p, 200000, 1);
  const int n = persistence_for_false_alarm_rate(calibration, rate, 40);
  EXPECT_EQ(n, 4);
  EXPECT_LE(alarm_share(calibration, n), rate);
  EXPECT_GT(alarm_share(calibration, n - 1), rate);
  const double fresh = alarm_share(bernoulli(p, 200000, 2), n);
  EXPECT_NEAR(fresh, std::pow(p, 4), 0.1 * std::pow(p, 4));

  // Gaussian noise through a ±1σ band: p = P(|x| > 1) = 0.3173, so again k = 4 for 1 %.
  std::mt19937 rng(3);
  std::normal_distribution<double> noise;
  Eigen::VectorXi outside(200000);
  for (Eigen::Index k = 0; k < outside.size(); ++k)
    outside[k] = std::abs(noise(rng)) > 1.0 ? 1 : 0;
  EXPECT_EQ(persistence_for_false_alarm_rate(outside, rate, 40), 4);
}

TEST(PersistenceTest, LimitsOfTheChoice) {
  EXPECT_EQ(persistence_for_false_alarm_rate(Eigen::VectorXi::Ones(100), 0.01, 40), 40);
  EXPECT_EQ(persistence_for_false_alarm_rate(Eigen::VectorXi::Zero(100), 0.0, 40), 1);
  EXPECT_EQ(persistence_for_false_alarm_rate(Eigen::VectorXi(0), 0.01, 40), 1);
  // One run of 7 in 1000 cycles: zero alarms needs 8; 0.2 % allows 6 (cycles 6 and 7 of the run).
  Eigen::VectorXi e = Eigen::VectorXi::Zero(1000);
  e.segment(100, 7).setOnes();
  EXPECT_EQ(persistence_for_false_alarm_rate(e, 0.0, 40), 8);
  EXPECT_EQ(persistence_for_false_alarm_rate(e, 0.002, 40), 6);
}

}  // namespace
