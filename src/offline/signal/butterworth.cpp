#include "offline/signal/butterworth.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// Runs the biquad in place over y (direct form II transposed), starting at steady state for y[0].
void run_forward(const Butterworth2& f, Eigen::VectorXd& y) {
  if (y.size() == 0) return;
  double z1 = (1.0 - f.b0) * y[0];  // steady state for a constant input (unit DC gain)
  double z2 = (f.b2 - f.a2) * y[0];
  for (Eigen::Index k = 0; k < y.size(); ++k) {
    const double x = y[k];
    const double out = f.b0 * x + z1;
    z1 = f.b1 * x - f.a1 * out + z2;
    z2 = f.b2 * x - f.a2 * out;
    y[k] = out;
  }
}

}  // namespace

Butterworth2 Butterworth2::low_pass(double cutoff_hz, double sample_rate_hz) {
  if (!(cutoff_hz > 0.0) || !(cutoff_hz < 0.5 * sample_rate_hz))
    throw Error("Butterworth low-pass: cutoff " + std::to_string(cutoff_hz) +
                " Hz must lie between 0 and half the sample rate (" +
                std::to_string(0.5 * sample_rate_hz) + " Hz)");
  const double k = std::tan(std::numbers::pi * cutoff_hz / sample_rate_hz);
  const double k2 = k * k;
  const double n = 1.0 / (1.0 + std::numbers::sqrt2 * k + k2);
  Butterworth2 f;
  f.b0 = k2 * n;
  f.b1 = 2.0 * f.b0;
  f.b2 = f.b0;
  f.a1 = 2.0 * (k2 - 1.0) * n;
  f.a2 = (1.0 - std::numbers::sqrt2 * k + k2) * n;
  return f;
}

Eigen::VectorXd filtfilt(const Butterworth2& filter, const Eigen::VectorXd& x,
                         double sample_rate_over_cutoff, Eigen::Index pad) {
  const Eigen::Index n = x.size();
  if (n < 2) return x;
  if (pad < 0)
    pad = static_cast<Eigen::Index>(std::max(9.0, std::round(3.0 * sample_rate_over_cutoff)));
  pad = std::min(pad, n - 1);
  Eigen::VectorXd y(n + 2 * pad);
  for (Eigen::Index m = 0; m < pad; ++m) {
    y[pad - 1 - m] = 2.0 * x[0] - x[m + 1];
    y[n + pad + m] = 2.0 * x[n - 1] - x[n - 2 - m];
  }
  y.segment(pad, n) = x;
  run_forward(filter, y);
  y.reverseInPlace();
  run_forward(filter, y);
  y.reverseInPlace();
  return y.segment(pad, n);
}

}  // namespace tpf::offline
