// The periodogram diagnose and the measured loop pick ripple periods with.
#include "offline/signal/periodogram.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tpf::offline {
namespace {

TEST(Periodogram, FindsThePlantedPeriodsPerRevolutionOnTheOutputAndTheMotor) {
  const int n = 4000;
  Eigen::VectorXd q(n), output(n), motor(n);
  for (int k = 0; k < n; ++k) {
    q[k] = -1.5 + 3.0 * k / (n - 1.0);
    output[k] = 0.3 * std::sin(7 * q[k] + 0.4) + 0.1 * q[k] + 0.05 * std::sin(11 * q[k]);
    motor[k] = 0.2 * std::cos(2 * 50.0 * q[k]);  // twice per motor revolution, gear ratio 50
  }
  EXPECT_EQ(dominant_cycles(q, output, 3, 64, 1.0), 7.0);
  EXPECT_EQ(dominant_cycles(q, motor, 1, 4, 50.0), 2.0);
  EXPECT_EQ(dominant_cycles(Eigen::VectorXd(), Eigen::VectorXd(), 5, 9, 1.0), 5.0);  // no data
}

TEST(Periodogram, ThePeriodMustFitInTheRangeOfMotion) {
  EXPECT_EQ(shortest_fitting_cycles(2 * M_PI / 5), 5);  // one period of 5/rev fits exactly
  EXPECT_EQ(shortest_fitting_cycles(0.38), 17);         // 2π/0.38 = 16.5
  EXPECT_EQ(shortest_fitting_cycles(10.0), 3);          // never below 3
  EXPECT_EQ(shortest_fitting_cycles(0.0), 1000000);     // no motion: no ripple fits
}

}  // namespace
}  // namespace tpf::offline
