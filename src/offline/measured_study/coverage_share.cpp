#include "offline/measured_study/coverage_share.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tpf::offline {

CoverageShare coverage_share(const JointSamples& fit, const Eigen::MatrixXd& fit_residual,
                             const JointSamples& heldout, const Eigen::MatrixXd& heldout_residual) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CoverageShare out;
  for (Eigen::Index j = 0; j < fit_residual.cols(); ++j) {
    double q_lo = inf, q_hi = -inf, v_lo = inf, v_hi = -inf;
    for (Eigen::Index k = 0; k < fit.size(); ++k) {
      if (!std::isfinite(fit_residual(k, j))) continue;
      q_lo = std::min(q_lo, fit.q(k, j)), q_hi = std::max(q_hi, fit.q(k, j));
      v_lo = std::min(v_lo, fit.dq(k, j)), v_hi = std::max(v_hi, fit.dq(k, j));
    }
    double n = 0, sum = 0, q_n = 0, q_sum = 0, v_n = 0, v_sum = 0;
    for (Eigen::Index k = 0; k < heldout.size() && q_lo <= q_hi; ++k) {
      const double r = heldout_residual(k, j);
      if (!std::isfinite(r)) continue;
      ++n, sum += r * r;
      if (heldout.q(k, j) < q_lo || heldout.q(k, j) > q_hi) ++q_n, q_sum += r * r;
      if (heldout.dq(k, j) < v_lo || heldout.dq(k, j) > v_hi) ++v_n, v_sum += r * r;
    }
    const bool any = n > 0;
    out.position_samples.push_back(any ? q_n / n : nan);
    out.position_error.push_back(any && sum > 0 ? q_sum / sum : nan);
    out.velocity_samples.push_back(any ? v_n / n : nan);
    out.velocity_error.push_back(any && sum > 0 ? v_sum / sum : nan);
    out.fit_velocity_min.push_back(q_lo <= q_hi ? v_lo : nan);
    out.fit_velocity_max.push_back(q_lo <= q_hi ? v_hi : nan);
  }
  return out;
}

}  // namespace tpf::offline
