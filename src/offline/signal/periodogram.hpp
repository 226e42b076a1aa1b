// Position-periodic content of a residual: which number of periods per revolution explains it
// best, and the shortest that fits in a range of motion.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

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

/// The central 98 % of q's range [rad] (0 for fewer than 3 samples).
double range_of_motion(const Eigen::VectorXd& q);

/// A ripple of the output angle that a residual holds (CandidateInputs::ripple_cycles,
/// ripple_periods): what diagnose's residual analysis and the measured study search.
struct OutputRipple {
  double cycles = 0;   ///< periods per revolution of q, fitted as a real number; 0 = not searched
  double periods = 0;  ///< cycles·range/2π: under 1 it cannot be told from an offset and a slope
  double range = 0;    ///< range_of_motion of q [rad]
};

/// fitted_cycles of r on q (scale 1) from half a period in q's range of motion (and 3 periods/rev:
/// below, gravity's sin q and cos q) to `highest`, when a period of `highest` fits in the range at
/// all (shortest_fitting_cycles); else cycles 0.
OutputRipple output_ripple(const Eigen::VectorXd& q, const Eigen::VectorXd& r, int highest = 64);

}  // namespace tpf::offline
