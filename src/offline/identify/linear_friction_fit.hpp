// Least squares of one joint's linear friction, every coefficient ≥ 0.
#pragma once

#include <Eigen/Core>

#include "offline/identify/stribeck_fit.hpp"

namespace tpf::offline {

/// Fits f = (τ_c + α_c|G|)·sgn(q̇) + (b + α_v|G|)·q̇ to the friction target f on moving samples
/// by least squares with τ_c, b, α_c, α_v ≥ 0 (α held at zero unless `fit_load`). Exact: the
/// non-negative optimum is the best of the unconstrained fits over the subsets of columns whose
/// coefficients come out ≥ 0. τ_s = τ_c in the result (a curve without a Stribeck dip). With
/// `nonnegative` false, the plain least-squares fit (coefficients of either sign).
JointStribeck fit_linear_friction(const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_gravity,
                                  const Eigen::VectorXd& target, bool fit_load,
                                  bool nonnegative = true);

}  // namespace tpf::offline
