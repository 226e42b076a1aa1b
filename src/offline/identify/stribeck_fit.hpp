// Nonlinear least squares (Ceres) of one joint's Stribeck curve with load dependence.
#pragma once

#include <Eigen/Core>

namespace tpf::offline {

/// Parameters of one joint, effort unit (see tpf::StribeckParameters).
struct JointStribeck {
  double coulomb = 0, static_friction = 0, stribeck_velocity = 0.05, stribeck_exponent = 1.5;
  double viscous = 0, load_coulomb = 0, load_viscous = 0;
};

/// Fits, on moving samples (|q̇| ≥ threshold, so sgn(q̇) is defined),
///   f = [τ_c + α_c|G| + (τ_s − τ_c)·exp(−|q̇/q̇_s|^δ)]·sgn(q̇) + (b + α_v|G|)·q̇
/// to the friction target f (effort minus the rigid-body prediction), with τ_c, τ_s, b, α ≥ 0,
/// q̇_s ∈ [1e-3, 2] rad/s, δ ∈ [0.3, 4]; the load terms are held at zero unless `fit_load`.
/// `start` holds the linear fit (τ_c, b, α). Cauchy loss at `robust_scale` (the effort noise
/// level) keeps stuck or bumped samples from pulling the curve.
JointStribeck fit_stribeck(const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_gravity,
                           const Eigen::VectorXd& target, const JointStribeck& start, bool fit_load,
                           double robust_scale);

}  // namespace tpf::offline
