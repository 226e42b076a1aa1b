// Joint velocity and acceleration derived from position, for logs that record no velocity.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

struct DerivedRates {
  Eigen::VectorXd velocity;      ///< [unit of q]/s
  Eigen::VectorXd acceleration;  ///< [unit of q]/s²
};

/// q̇ and q̈ of q(t): per contiguous segment (no NaN, no gap > 1.5 median steps), the position is
/// low-passed by a 2nd-order Butterworth run forward and backward (zero_phase_low_pass: phase 0,
/// |H|² = −6 dB at `cutoff_hz`, fs = 1 / median step), then differenced on the recorded time
/// stamps: q̇[k] = (v[k+1] − v[k−1]) / (t[k+1] − t[k−1]) and
/// q̈[k] = 2·((v[k+1] − v[k]) / h₊ − (v[k] − v[k−1]) / h₋) / (h₊ + h₋), h₋ and h₊ the steps
/// before and after k (exact for a parabola on uneven steps). The first and last sample of each
/// segment are NaN: no difference is taken across a gap. Throws tpf::Error on a cut-off outside
/// (0, fs/2) or sizes that differ.
DerivedRates derive_rates(const Eigen::VectorXd& t, const Eigen::VectorXd& q, double cutoff_hz);

}  // namespace tpf::offline
