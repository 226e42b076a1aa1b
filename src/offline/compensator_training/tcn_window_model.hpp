// Full-window (non-streaming) TCN forward pass and its exact gradient, for training.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "offline/compensator_training/tcn_parameters.hpp"

namespace tpf::offline {

/// Buffers of one window's forward and backward pass; reused across windows to avoid allocation.
/// Each block level has its own buffers (their shapes differ between levels), so a window of the
/// length of the previous one allocates nothing.
template <typename S>
struct BasicTcnWindowWorkspace {
  using Matrix = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
  std::vector<Matrix> activations;  ///< X_0 (normalised input) … X_L, channels × time
  /// Per block, the K lagged copies of its input stacked (K·C_in × T_out), so that one GEMM
  /// [W_0 … W_{K−1}]·stack does all taps (not filled where float_gemm16 reads them in place).
  std::vector<Matrix> stacked_inputs;
  std::vector<Matrix> stacked_weights;     ///< per block, [W_0 … W_{K−1}]: C_out × K·C_in
  std::vector<Matrix> transposed_weights;  ///< their transposes, for float_gemm16
  /// Where float_gemm16 reads a block's lagged inputs (no stacked copy; stacked_inputs unused).
  std::vector<std::ptrdiff_t> offsets;
  std::vector<Matrix> weight_gradients;  ///< per block, ∂L/∂[W_0 … W_{K−1}]
  std::vector<Matrix> stack_gradients;   ///< per block, ∂L/∂stack
  Matrix low;                            ///< Out × M
  Matrix high;                           ///< Out × M
  std::vector<Matrix> input_gradients;   ///< ∂L/∂X_0 … ∂L/∂X_L during the backward pass
};
using TcnWindowWorkspace = BasicTcnWindowWorkspace<double>;

/// A read-only window (columns = time); S is deduced from the parameters, not from this.
template <typename S>
using TcnWindowMatrix =
    std::type_identity_t<Eigen::Ref<const Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>>>;

/// "Valid" causal forward pass over a window of W ≥ R normalised inputs (In × W, column = time):
///   X_{l+1}[:, i] = ReLU(b_l + Σ_j W_{l,j}·X_l[:, i + (K−1−j)·d_l] + P_l·X_l[:, i + (K−1)·d_l]),
/// which shortens the window by (K − 1)·d_l per block; the heads then give low and high for the
/// last M = W − R + 1 time steps (column i ↔ input column i + R − 1). Exactly the streaming
/// Tcn::step outputs when the window holds the true past (no padding anywhere).
/// Both functions are instantiated for S = double and float.
template <typename S>
void tcn_window_forward(const BasicTcnParameters<S>& parameters, const TcnWindowMatrix<S>& inputs,
                        BasicTcnWindowWorkspace<S>& workspace);

/// Forward pass plus the window loss
///   L = w_low·Σ s²⊙(low − target_low)² + w_high·Σ s²⊙(high − target_high)²   (sums over Out × M),
/// with per-sample weights s² (`sample_scale` = s, Out × M, the square root of the weight; null:
/// s = 1), and, if `gradient` is not null, ∂L/∂θ for every tensor θ added into `*gradient` (same
/// shapes as `parameters`, by backpropagation through the window). Returns L.
template <typename S>
double tcn_window_loss(const BasicTcnParameters<S>& parameters, const TcnWindowMatrix<S>& inputs,
                       const TcnWindowMatrix<S>& target_low, const TcnWindowMatrix<S>& target_high,
                       double weight_low, double weight_high, BasicTcnWindowWorkspace<S>& workspace,
                       std::type_identity_t<BasicTcnParameters<S>>* gradient,
                       const TcnWindowMatrix<S>* sample_scale = nullptr);

}  // namespace tpf::offline
