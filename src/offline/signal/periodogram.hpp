// Position-periodic content of a residual: which number of periods per revolution explains it
// best, and the shortest that fits in a range of motion.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

/// The integer n in [lo, hi] whose sin/cos of n·scale·q best explains r (the periodogram's peak,
/// |Σ r·e^(−i n scale q)|²); `scale` is 1 for the output angle, the gear ratio for the motor's.
double dominant_cycles(const Eigen::VectorXd& q, const Eigen::VectorXd& r, int lo, int hi,
                       double scale);

/// The real n in [lo, hi] whose sin/cos of n·scale·q, fitted by least squares beside an offset
/// and a slope in q, explain the largest part of r's sum of squares. That sum is evaluated on a
/// grid of 1/6 of the spectral width 2π/(scale·span of q) (at most 8192 points), and its best
/// point refined by golden-section search between its neighbours. 0 when q does not move or
/// holds fewer than 3 samples. O(samples × grid points), without a trigonometric call per point.
double fitted_cycles(const Eigen::VectorXd& q, const Eigen::VectorXd& r, double lo, double hi,
                     double scale);

/// The share of r's sum of squares, beside an offset and a slope in q (what those leave), that
/// sin/cos of n·scale·q explain by least squares: fitted_cycles' criterion, in [0, 1].
double explained_share(const Eigen::VectorXd& q, const Eigen::VectorXd& r, double n, double scale);

/// The fewest periods per revolution (at least 3) whose period fits in `range` [rad]: a longer
/// period cannot be told from an offset or a slope over that motion. At most 10⁶ (no motion).
int shortest_fitting_cycles(double range);

}  // namespace tpf::offline
