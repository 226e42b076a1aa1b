#include "offline/train/zero_phase_lowpass.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

struct Biquad {
  double b0, b1, b2, a1, a2;  // y = b0·x + z1; z1 ← b1·x − a1·y + z2; z2 ← b2·x − a2·y
};

Biquad butterworth_lowpass(double cutoff_hz, double sample_rate_hz) {
  const double k = std::tan(std::numbers::pi * cutoff_hz / sample_rate_hz);
  const double norm = 1.0 / (1.0 + std::numbers::sqrt2 * k + k * k);
  const double b0 = k * k * norm;
  return {b0, 2.0 * b0, b0, 2.0 * (k * k - 1.0) * norm,
          (1.0 - std::numbers::sqrt2 * k + k * k) * norm};
}

/// Direct form II transposed, starting in the steady state of a constant input x[0].
void filter_in_place(const Biquad& f, Eigen::VectorXd& x) {
  if (x.size() == 0) return;
  double z2 = (f.b2 - f.a2) * x[0];
  double z1 = (f.b1 - f.a1) * x[0] + z2;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double in = x[i];
    const double out = f.b0 * in + z1;
    z1 = f.b1 * in - f.a1 * out + z2;
    z2 = f.b2 * in - f.a2 * out;
    x[i] = out;
  }
}

}  // namespace

Eigen::VectorXd zero_phase_lowpass(const Eigen::Ref<const Eigen::VectorXd>& x, double cutoff_hz,
                                   double sample_rate_hz) {
  if (!(sample_rate_hz > 0.0) || !(cutoff_hz > 0.0) || !(cutoff_hz < 0.5 * sample_rate_hz)) {
    throw Error::at("zero_phase_lowpass", 0, "cutoff_hz",
                    "must lie in (0, sample_rate/2), got " + std::to_string(cutoff_hz) + " Hz at " +
                        std::to_string(sample_rate_hz) + " Hz");
  }
  const Eigen::Index n = x.size();
  if (n == 0) return {};
  const Eigen::Index pad = std::min<Eigen::Index>(
      n - 1, static_cast<Eigen::Index>(std::ceil(3.0 * sample_rate_hz / cutoff_hz)));
  Eigen::VectorXd y(n + 2 * pad);
  for (Eigen::Index k = 0; k < pad; ++k) {
    y[pad - 1 - k] = 2.0 * x[0] - x[k + 1];
    y[pad + n + k] = 2.0 * x[n - 1] - x[n - 2 - k];
  }
  y.segment(pad, n) = x;

  const Biquad f = butterworth_lowpass(cutoff_hz, sample_rate_hz);
  filter_in_place(f, y);
  y.reverseInPlace();
  filter_in_place(f, y);
  y.reverseInPlace();
  return y.segment(pad, n);
}

}  // namespace tpf::offline
