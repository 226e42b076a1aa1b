// Zero-phase smoothing and acceleration from velocity, segment-wise across gaps and NaNs.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

/// Zero-phase 2nd-order Butterworth low-pass (filtfilt) of x(t), applied separately to every
/// contiguous segment (contiguous_segments: no NaN, no gap > 1.5 median steps); fs = 1/median step.
/// NaN stays NaN; values are never carried across a gap. Segments of one sample pass unchanged.
Eigen::VectorXd zero_phase_low_pass(const Eigen::VectorXd& t, const Eigen::VectorXd& x,
                                    double cutoff_hz);

/// Joint acceleration [rad/s²] from joint velocity dq [rad/s] sampled at t [s], for logs without
/// ddq<j>: per contiguous segment, v = filtfilt_Butterworth2(dq, cutoff_hz) and the central
/// difference ddq[k] = (v[k+1] − v[k−1]) / (t[k+1] − t[k−1]). Zero phase; the gain at angular
/// frequency ω is ω·|H(ω)|²·sin(ωh)/(ωh) with h the sample step. The first and last sample
/// of every segment (next to a gap, a NaN or the log's ends) are NaN: no difference is ever taken
/// across a gap. Throws tpf::Error on size mismatch or a cutoff outside (0, fs/2).
Eigen::VectorXd derive_acceleration(const Eigen::VectorXd& t, const Eigen::VectorXd& dq,
                                    double cutoff_hz);

/// zero_phase_low_pass and derive_acceleration with t's median step given (median_step(t),
/// computed once by a caller that filters several signals of one t): the same results.
Eigen::VectorXd zero_phase_low_pass(const Eigen::VectorXd& t, const Eigen::VectorXd& x,
                                    double cutoff_hz, double median_step_s);
Eigen::VectorXd derive_acceleration(const Eigen::VectorXd& t, const Eigen::VectorXd& dq,
                                    double cutoff_hz, double median_step_s);

}  // namespace tpf::offline
