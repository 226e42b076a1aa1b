// The causal first-order low-pass the measured loop runs the motor current through.
#include "offline/signal/causal_low_pass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tpf::offline {
namespace {

TEST(CausalLowPass, StepResponseRestartsAtEachFileAndAfterANaN) {
  const int n = 400;
  Eigen::VectorXd t(n), x(n);
  for (int k = 0; k < n; ++k) {
    t[k] = 0.001 * k;
    x[k] = k < 100 ? 0.0 : 1.0;  // a unit step at row 100
  }
  x[300] = std::numeric_limits<double>::quiet_NaN();
  const double tau = 0.02;
  const Eigen::VectorXd y = causal_low_pass(t, x, tau, {0, 200});
  for (int k = 100; k < 200; ++k)  // y = 1 − exp(−(t − t_step)/τ) exactly, sampled
    EXPECT_NEAR(y[k], 1.0 - std::exp(-(t[k] - t[99]) / tau), 1e-12) << k;
  EXPECT_EQ(y[200], 1.0);  // a new file starts at its own first value
  EXPECT_TRUE(std::isnan(y[300]));
  EXPECT_EQ(y[301], 1.0);                                         // and so does the row after a NaN
  const Eigen::VectorXd unfiltered = causal_low_pass(t, x, 0.0);  // τ ≤ 0: x unchanged
  for (int k = 0; k < n; ++k)
    EXPECT_TRUE(unfiltered[k] == x[k] || (std::isnan(unfiltered[k]) && std::isnan(x[k]))) << k;
}

}  // namespace
}  // namespace tpf::offline
