// The error floor of a model of the drive loss from the motion: the part of the residual
// K_t·i − d − τ_sensor above a cut-off that the motion does not reach (the current's noise).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/log/log.hpp"

namespace tpf::offline {

/// Per column of `x` (samples × joints, rows = log's rows): RMS over the finite samples of
/// x − zero_phase_low_pass(x, cutoff_hz), the low-pass run within each file of `log` (and each
/// NaN-free stretch) on the times `t`; NaN for a column without finite samples.
std::vector<double> high_frequency_rms(const Log& log, const Eigen::VectorXd& t,
                                       const Eigen::MatrixXd& x, double cutoff_hz);

/// Per column of `x`: RMS below `low_hz`, between `low_hz` and `high_hz`, above `high_hz` and in
/// all, over its finite samples (each split as high_frequency_rms does; the parts are squared
/// differences of those, so low² + mid² + high² = total²).
struct BandRms {
  std::vector<double> low, mid, high, total;
};
BandRms band_rms(const Log& log, const Eigen::VectorXd& t, const Eigen::MatrixXd& x, double low_hz,
                 double high_hz);

/// RMS over the finite samples of x (NaN when none).
double finite_rms(const Eigen::Ref<const Eigen::VectorXd>& x);

/// finite_rms of each column.
std::vector<double> finite_rms_per_column(const Eigen::MatrixXd& x);

}  // namespace tpf::offline
