// The zero-phase Butterworth that splits the TCN target into low and high parts (the trainer
// calls filtfilt(Butterworth2::low_pass(f_c, f_s), x, f_s/f_c)): DC gain 1,
// |H|² = 1/(1 + (tan(πf/f_s)/tan(πf_c/f_s))⁴), no phase shift.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "offline/signal/butterworth.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

Eigen::VectorXd zero_phase_lowpass(const Eigen::VectorXd& x, double fc, double fs) {
  return filtfilt(Butterworth2::low_pass(fc, fs), x, fs / fc);
}

Eigen::VectorXd cosine(double f, double fs, Eigen::Index n) {
  Eigen::VectorXd x(n);
  for (Eigen::Index i = 0; i < n; ++i)
    x[i] = std::cos(2 * std::numbers::pi * f * i / fs);
  return x;
}

TEST(ZeroPhaseLowpass, KeepsAConstantExactly) {
  const Eigen::VectorXd x = Eigen::VectorXd::Constant(500, 1.7);
  EXPECT_LT((zero_phase_lowpass(x, 2.0, 400.0) - x).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ZeroPhaseLowpass, GainIsButterworthSquaredWithoutPhaseShift) {
  const double fs = 400.0, fc = 5.0;
  const Eigen::Index n = 8000;
  for (const double f : {0.5, 5.0, 20.0}) {
    const Eigen::VectorXd x = cosine(f, fs, n);
    const Eigen::VectorXd y = zero_phase_lowpass(x, fc, fs);
    const double warped =
        std::tan(std::numbers::pi * f / fs) / std::tan(std::numbers::pi * fc / fs);
    const double gain = 1.0 / (1.0 + std::pow(warped, 4));
    // Away from the edges the output is gain·x sample by sample (zero phase).
    const Eigen::VectorXd middle = y.segment(2000, 4000) - gain * x.segment(2000, 4000);
    EXPECT_LT(middle.cwiseAbs().maxCoeff(), 2e-3 * std::max(gain, 0.01)) << "f = " << f;
  }
}

TEST(ZeroPhaseLowpass, RefusesACutoffAboveNyquist) {
  EXPECT_THROW(zero_phase_lowpass(Eigen::VectorXd::Ones(10), 250.0, 400.0), Error);
}

}  // namespace
}  // namespace tpf::offline
