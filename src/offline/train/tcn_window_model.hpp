// Full-window (non-streaming) TCN forward pass and its exact gradient, for training.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/train/tcn_parameters.hpp"

namespace tpf::offline {

/// Buffers of one window's forward and backward pass; reused across windows to avoid allocation.
struct TcnWindowWorkspace {
  std::vector<Eigen::MatrixXd> activations;  ///< X_0 (normalised input) … X_L, channels × time
  Eigen::MatrixXd low;                       ///< Out × M
  Eigen::MatrixXd high;                      ///< Out × M
  Eigen::MatrixXd upstream;                  ///< ∂L/∂X_{l+1} during the backward pass
  Eigen::MatrixXd downstream;                ///< ∂L/∂X_l during the backward pass
};

/// "Valid" causal forward pass over a window of W ≥ R normalised inputs (In × W, column = time):
///   X_{l+1}[:, i] = ReLU(b_l + Σ_j W_{l,j}·X_l[:, i + (K−1−j)·d_l] + P_l·X_l[:, i + (K−1)·d_l]),
/// which shortens the window by (K − 1)·d_l per block; the heads then give low and high for the
/// last M = W − R + 1 time steps (column i ↔ input column i + R − 1). Exactly the streaming
/// Tcn::step outputs when the window holds the true past (no padding anywhere).
void tcn_window_forward(const TcnParameters& parameters,
                        const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                        TcnWindowWorkspace& workspace);

/// Forward pass plus the window loss
///   L = w_low·Σ (low − target_low)² + w_high·Σ (high − target_high)²   (sums over Out × M),
/// and, if `gradient` is not null, ∂L/∂θ for every tensor θ added into `*gradient` (same shapes
/// as `parameters`, by backpropagation through the window). Returns L.
double tcn_window_loss(const TcnParameters& parameters,
                       const Eigen::Ref<const Eigen::MatrixXd>& inputs,
                       const Eigen::Ref<const Eigen::MatrixXd>& target_low,
                       const Eigen::Ref<const Eigen::MatrixXd>& target_high, double weight_low,
                       double weight_high, TcnWindowWorkspace& workspace, TcnParameters* gradient);

}  // namespace tpf::offline
