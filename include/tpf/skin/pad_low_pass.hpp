// First-order IIR low-pass of one pad's pressure, with the coefficient taken from each sample's
// period so that dropped cycles do not change the cut-off.
#pragma once

#include <cmath>
#include <numbers>

namespace tpf {

/// Coefficient of the first-order low-pass y_k = y_{k−1} + α·(x_k − y_{k−1}) for cut-off f_c [Hz]
/// and sample period h [s]: α = 1 − exp(−2π·f_c·h) (the exact discretisation of
/// τ·ẏ = x − y with τ = 1/(2π·f_c) under a zero-order hold). α ∈ (0, 1) for h > 0.
template <typename S>
S low_pass_coefficient(S cutoff_hz, S period_s) noexcept {
  using std::exp;
  return S(1) - exp(-S(2) * std::numbers::pi_v<S> * cutoff_hz * period_s);
}

/// The standard deviation of the filter's output for white input noise of standard deviation
/// σ_in at a fixed α: σ_out = σ_in·√(α / (2 − α)).
template <typename S>
S low_pass_noise_gain(S alpha) noexcept {
  using std::sqrt;
  return sqrt(alpha / (S(2) - alpha));
}

/// y_k = y_{k−1} + α(h_k)·(x_k − y_{k−1}), α from low_pass_coefficient. Allocation-free.
template <typename S>
class PadLowPass {
 public:
  explicit PadLowPass(S cutoff_hz = S(40)) noexcept : cutoff_hz_(cutoff_hz) {}

  /// Sets the output to x (the first sample after start or a reset).
  void reset(S x) noexcept { y_ = x; }

  /// Advances by one sample x taken h seconds after the previous one; returns the new output.
  S update(S x, S period_s) noexcept {
    return update_with_coefficient(x, low_pass_coefficient(cutoff_hz_, period_s));
  }

  /// The same with α = low_pass_coefficient(cutoff_hz(), h) already computed (one exp per sample
  /// for all pads that share the cut-off).
  S update_with_coefficient(S x, S alpha) noexcept {
    y_ += alpha * (x - y_);
    return y_;
  }

  S value() const noexcept { return y_; }
  S cutoff_hz() const noexcept { return cutoff_hz_; }

 private:
  S cutoff_hz_;
  S y_ = S(0);
};

}  // namespace tpf
