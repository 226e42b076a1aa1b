// Causal acceleration from velocity: ramps, sines, dropped cycles.
#include "tpf/estimation/acceleration_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "support/constants.hpp"

namespace {

using tpf::test::kPeriod;
using Vec1 = tpf::JointVector<double, 1>;

TEST(AccelerationFilter, RampGivesItsSlope) {
  tpf::AccelerationFilter<double, 1> f;
  f.reset(Vec1::Zero());
  for (int k = 1; k <= 400; ++k)
    f.update(Vec1::Constant(2.5 * k * kPeriod), kPeriod);
  EXPECT_NEAR(f.value()[0], 2.5, 1e-9);
}

TEST(AccelerationFilter, LowFrequencySineMatchesTheDesignedTransferFunction) {
  const double w = 2 * std::numbers::pi * 1.0;  // 1 Hz, well below the 20 Hz cut-off
  tpf::AccelerationFilter<double, 1> f(20.0, 0.8);
  f.reset(Vec1::Zero());
  double peak = 0;
  for (int k = 1; k <= 4000; ++k) {
    const double y = f.update(Vec1::Constant(std::sin(w * k * kPeriod)), kPeriod)[0];
    if (k > 2000) peak = std::max(peak, std::abs(y));
  }
  // |s·ω_c²/(s² + 2ζω_c s + ω_c²)| at s = jω ≈ ω (within 1 % at ω/ω_c = 0.05).
  const double wc = 2 * std::numbers::pi * 20.0;
  const std::complex<double> s(0, w);
  const double gain = std::abs(s * wc * wc / (s * s + 2 * 0.8 * wc * s + wc * wc));
  EXPECT_NEAR(peak, gain, 0.01 * gain);
  EXPECT_NEAR(peak, w, 0.02 * w);
}

TEST(AccelerationFilter, StaysBoundedAcrossALongGap) {
  tpf::AccelerationFilter<double, 1> f;
  f.reset(Vec1::Zero());
  f.update(Vec1::Constant(1.0), 0.5);  // 200 cycles lost, then a velocity step
  EXPECT_TRUE(std::isfinite(f.value()[0]));
  EXPECT_LT(std::abs(f.value()[0]), 1.0 / 0.5);
}

}  // namespace
