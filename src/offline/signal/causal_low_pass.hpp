// A causal first-order low-pass, as a controller could run it on the motor current.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace tpf::offline {

/// y[k] = y[k−1] + (1 − exp(−(t[k] − t[k−1])/tau))·(x[k] − y[k−1]), restarted (y = x) at each
/// of `starts` (rows where a file begins; the first row always) and after a NaN, which stays NaN.
/// tau ≤ 0 returns x unchanged.
Eigen::VectorXd causal_low_pass(const Eigen::VectorXd& t, const Eigen::VectorXd& x, double tau,
                                const std::vector<Eigen::Index>& starts = {0});

}  // namespace tpf::offline
