// Fixed-size weights of the streaming TCN, with the input normalisation already folded in.
#pragma once

#include <Eigen/Core>
#include <array>

namespace tpf {

/// Weights of `Tcn<S, In, Hidden, Levels, Kernel, Out>` (see tcn.hpp for the equations).
///
/// Taps are indexed by lag: `taps[j]` multiplies the block input at t − j·d_l. Block 0 maps the
/// raw input (In channels, units as given: rad, rad/s, rad/s², N·m) to Hidden channels; its weights
/// and bias have absorbed the normalisation x̃ = (x − μ)/σ, and its skip path is the 1×1 matrix
/// `input_projection` (the folded projection, or the folded identity diag(1/σ) when In == Hidden).
/// Blocks 1 … Levels−1 map Hidden → Hidden with an identity skip path.
///
/// The 64-channel double version is ≈ 650 kB: hold it (or the Tcn) on the heap, e.g. via
/// std::make_unique, never in a small thread stack.
template <typename S, int In, int Hidden, int Levels, int Kernel, int Out>
struct TcnWeights {
  using InputTap = Eigen::Matrix<S, Hidden, In>;
  using HiddenTap = Eigen::Matrix<S, Hidden, Hidden>;
  using HiddenVector = Eigen::Matrix<S, Hidden, 1>;
  using Head = Eigen::Matrix<S, Out, Hidden>;
  using OutputVector = Eigen::Matrix<S, Out, 1>;

  std::array<InputTap, Kernel> input_taps{};  ///< block 0 taps, raw-input units folded in
  InputTap input_projection = InputTap::Zero();
  HiddenVector input_bias = HiddenVector::Zero();
  std::array<std::array<HiddenTap, Kernel>, Levels - 1> taps{};  ///< taps[l − 1][j], block l ≥ 1
  std::array<HiddenVector, Levels - 1> bias{};
  Head low_weight = Head::Zero();  ///< low-frequency head on the last block's output
  OutputVector low_bias = OutputVector::Zero();
  Head high_weight = Head::Zero();  ///< high-frequency head
  OutputVector high_bias = OutputVector::Zero();

  TcnWeights() {
    for (auto& w : input_taps)
      w.setZero();
    for (auto& block : taps)
      for (auto& w : block)
        w.setZero();
    for (auto& b : bias)
      b.setZero();
  }
};

}  // namespace tpf
