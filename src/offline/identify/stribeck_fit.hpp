// Nonlinear least squares (Ceres) of one joint's Stribeck curve with load dependence.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace tpf::offline {

/// Parameters of one joint, N·m (see tpf::StribeckParameters).
struct JointStribeck {
  double coulomb = 0, static_friction = 0, stribeck_velocity = 0.05, stribeck_exponent = 1.5;
  double viscous = 0, load_coulomb = 0, load_viscous = 0;
};

/// The fitted curve and the names of the parameters that ended at a bound ("τ_s at its lower
/// bound 0", …): a bound that binds means the curve could not take the shape the data asked for.
struct StribeckFit {
  JointStribeck curve;
  std::vector<std::string> at_bound;
};

/// Fits, on moving samples (|q̇| ≥ threshold, so sgn(q̇) is defined),
///   f = [τ_c + α_c|G| + (τ_s − τ_c)·exp(−|q̇/q̇_s|^δ)]·sgn(q̇) + (b + α_v|G|)·q̇
/// to the friction target f (effort minus the rigid-body prediction), with τ_c, τ_s, b, α ≥ 0,
/// q̇_s ∈ [1e-3, 2] rad/s, δ ∈ [0.3, 4]; the load terms are held at zero unless `fit_load`.
/// `start` holds the linear fit (τ_c, b, α). With `cauchy_scale` c > 0 the loss is Cauchy's,
/// c²·ln(1 + r²/c²) per sample: residuals well above c (the onsets and reversals, where the
/// friction of a joint that has just started is not yet the sliding curve's) weigh less, and the
/// curve follows the sliding samples; c = 0 is plain least squares.
StribeckFit fit_stribeck(const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_gravity,
                         const Eigen::VectorXd& target, const JointStribeck& start, bool fit_load,
                         double cauchy_scale = 0.0);

/// The same fit, one start: `curve` (a curve fitted on part of these samples), refined.
StribeckFit refine_stribeck(const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_gravity,
                            const Eigen::VectorXd& target, const JointStribeck& curve,
                            bool fit_load, double cauchy_scale = 0.0);

}  // namespace tpf::offline
