// tpf::sin_cos, the joint rotations' sine and cosine, against the library's std::sin/std::cos.
#include "tpf/kinematics/sin_cos.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace tpf {
namespace {

TEST(SinCos, WithinAnUlpOfTheLibraryOverJointAngles) {
  std::mt19937_64 rng(91);
  for (const double range : {0.1, 1.0, 3.2, 7.0, 100.0, 9e4}) {
    std::uniform_real_distribution<double> u(-range, range);
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
      const double x = u(rng);
      double s, c;
      sin_cos(x, s, c);
      worst = std::max({worst, std::abs(s - std::sin(x)), std::abs(c - std::cos(x))});
    }
    EXPECT_LE(worst, 2.3e-16) << "range ±" << range;  // one ulp at 1 is 2.2e-16
  }
}

TEST(SinCos, ExactAtZeroAndRightInEveryQuadrant) {
  double s, c;
  sin_cos(0.0, s, c);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(c, 1.0);
  for (int k = -8; k <= 8; ++k) {  // the quadrant swaps and signs
    const double x = k * M_PI / 4 + 0.1;
    sin_cos(x, s, c);
    EXPECT_NEAR(s, std::sin(x), 2.3e-16) << x;
    EXPECT_NEAR(c, std::cos(x), 2.3e-16) << x;
  }
}

TEST(SinCos, LargeAndNonFiniteAnglesFallBackToTheLibrary) {
  double s, c;
  sin_cos(1e7 + 0.3, s, c);
  EXPECT_EQ(s, std::sin(1e7 + 0.3));
  EXPECT_EQ(c, std::cos(1e7 + 0.3));
  sin_cos(std::numeric_limits<double>::quiet_NaN(), s, c);
  EXPECT_TRUE(std::isnan(s) && std::isnan(c));
  float sf, cf;
  sin_cos(0.7f, sf, cf);
  EXPECT_NEAR(sf, std::sin(0.7f), 1e-7f);
  EXPECT_NEAR(cf, std::cos(0.7f), 1e-7f);
}

}  // namespace
}  // namespace tpf
