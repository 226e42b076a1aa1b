// Zero-phase low-pass filter used to split the friction residual into low and high parts.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

/// Second-order Butterworth low-pass (bilinear transform, cut-off pre-warped), run forward then
/// backward (filtfilt), so the result has zero phase and magnitude
///   |H(f)|² = 1/(1 + (tan(πf/f_s)/tan(πf_c/f_s))⁴) ≈ 1/(1 + (f/f_c)⁴) for f ≪ f_s
/// (exactly 1/2 at f_c, DC gain 1). Edge transients are suppressed by padding both ends with the
/// odd reflection 2·x_0 − x_k of ⌈3·f_s/f_c⌉ samples (fewer if the signal is shorter) and by
/// starting each pass in the steady state of its first sample.
///
/// x: samples at f_s [Hz]; cutoff_hz in (0, f_s/2). Throws tpf::Error on a bad cut-off.
Eigen::VectorXd zero_phase_lowpass(const Eigen::Ref<const Eigen::VectorXd>& x, double cutoff_hz,
                                   double sample_rate_hz);

}  // namespace tpf::offline
