// The ratio of each coupled-motor candidate (CoupledMotorColumns), fitted to the declared model's
// residual before the candidate library's columns are built, as a ripple's frequency is.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/common/run_time_types.hpp"
#include "offline/effects/candidate_inputs.hpp"
#include "offline/samples/joint_samples.hpp"
#include "tpf/dynamics/base_parameters.hpp"

namespace tpf::offline {

/// For each adjacent pair of joints (i, i + 1) whose motors `model` declares uncoupled (and of
/// one type: both revolute or both prismatic): the
/// direction (a, b) of a motor velocity θ̇ = a·q̇_i + b·q̇_{i+1} whose friction through Cᵀ,
/// [a; b]·(τ_c sgn θ̇ + b_v θ̇), explains most of `residual` (effort − the declared linear fit)
/// beside each joint's own Coulomb and viscous columns, by weighted least squares (joint weights
/// `weights`) on the moving training samples (≤ 5000 of them): a grid of 1° over the half turn
/// of directions, refined by golden-section search between the best point's neighbours. The sign
/// of sgn θ̇ — where the motor reverses — fixes the direction, the joints' shares its scale.
/// Normalised to max(|a|, |b|) = 1; a direction within 0.05 of a joint's own (|c| < 0.05) is
/// no coupling and is left out. `armature` is set when [a; b]·(a q̈_i + b q̈_{i+1}) lies outside
/// the span of the rigid body's base columns `base` (tested on regressors at random states).
std::vector<CoupledMotorCandidate> fit_coupled_motors(
    const ModelX& model, const BaseParameters& base, const JointSamples& samples,
    const Eigen::MatrixXd& residual, const Eigen::VectorXd& weights, double static_velocity);

}  // namespace tpf::offline
