// A starting point for training: a network that already predicts the static-friction baseline.
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "offline/compensator_training/tcn_parameters.hpp"

namespace tpf::offline {

/// He-initialised parameters (init_tcn_parameters(architecture, seed)) in which 2 hidden channels
/// per output o carry the baseline input x_b(o) = τ̂_fric,s of that joint unchanged to the heads:
///   block 0:  u±_o = ReLU(±x̃_b(o)),  x̃ = (x − mean)/std (the trainer's normalisation);
///   blocks ≥ 1: those channels have zero taps and bias, so the identity skip keeps ReLU(u) = u;
///   low head: y_o = std_b·(u+_o − u−_o) + mean_b = τ̂.
/// The network thus starts as the model-free static estimate (exact at rest, where the target is
/// the held friction) and training only has to learn what the baseline misses (break-away, the
/// moving residual). baseline_input[o] is the input column of output o's τ̂_fric,s (3N + o for the
/// all-joints network, 3 for a per-joint one). Needs hidden ≥ 2·outputs. Throws tpf::Error
/// otherwise.
TcnParameters baseline_start(const TcnArchitecture& architecture, std::uint64_t seed,
                             const Eigen::VectorXd& input_mean, const Eigen::VectorXd& input_std,
                             const Eigen::VectorXi& baseline_input);

}  // namespace tpf::offline
