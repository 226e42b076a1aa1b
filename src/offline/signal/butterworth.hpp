// Second-order Butterworth low-pass and its zero-phase (forward–backward) application.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

/// Biquad y[k] = b0·x[k] + b1·x[k−1] + b2·x[k−2] − a1·y[k−1] − a2·y[k−2] (a0 = 1).
struct Butterworth2 {
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;

  /// 2nd-order Butterworth low-pass by the bilinear transform with pre-warping:
  /// K = tan(π·fc/fs), n = 1 / (1 + √2·K + K²), b0 = b2 = K²·n, b1 = 2·b0,
  /// a1 = 2(K² − 1)·n, a2 = (1 − √2·K + K²)·n. Unit DC gain, −3 dB at fc.
  /// Throws tpf::Error unless 0 < cutoff_hz < sample_rate_hz / 2.
  static Butterworth2 low_pass(double cutoff_hz, double sample_rate_hz);
};

/// Zero-phase filtering of one contiguous, NaN-free stretch (like MATLAB/SciPy filtfilt):
/// the stretch is extended at both ends by an odd reflection of `pad` samples
/// (x_pad[−m] = 2·x[0] − x[m]), run forward with the filter state at steady state for the first
/// padded value, reversed, run again the same way, reversed and trimmed. Net response |H(f)|²,
/// phase 0 (−6 dB at fc). pad < 0 selects min(n − 1, max(9, 3·fs/fc)) from the filter's own
/// time constant; `sample_rate_over_cutoff` is fs/fc for that choice.
Eigen::VectorXd filtfilt(const Butterworth2& filter, const Eigen::VectorXd& x,
                         double sample_rate_over_cutoff, Eigen::Index pad = -1);

}  // namespace tpf::offline
