// Position-periodic content of a residual: which number of periods per revolution explains it
// best, and the shortest that fits in a range of motion.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

/// The integer n in [lo, hi] whose sin/cos of n·scale·q best explains r (the periodogram's peak,
/// |Σ r·e^(−i n scale q)|²); `scale` is 1 for the output angle, the gear ratio for the motor's.
double dominant_cycles(const Eigen::VectorXd& q, const Eigen::VectorXd& r, int lo, int hi,
                       double scale);

/// The fewest periods per revolution (at least 3) whose period fits in `range` [rad]: a longer
/// period cannot be told from an offset or a slope over that motion. At most 10⁶ (no motion).
int shortest_fitting_cycles(double range);

}  // namespace tpf::offline
