// The one network for all joints (`tpf train` without --per-joint) with its sizes read at
// start-up: inputs 5n and outputs n for the arm's joint count n, any n. The controllers' Tcn has
// them compiled (AllJointsTcn names a fixed joint count); the offline tools run one estimator for
// every arm, so they evaluate the same network with sizes chosen at run time.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf::offline {

/// A streaming TCN of run-time sizes, in double: the equations, ring buffers and input handling
/// of tpf::Tcn (tcn.hpp) — a non-finite input is replaced by the last finite one — with the sums
/// taken by Eigen's run-time kernels (equal to Tcn<double, …>'s to rounding). Satisfies
/// FrictionCompensator<AllJointsNetwork, double, Eigen::Dynamic> once loaded. Allocation-free
/// step; load allocates.
class AllJointsNetwork {
 public:
  using Input = Eigen::VectorXd;
  using Output = Eigen::VectorXd;

  /// Start-up: the weights of `file` for `joints` joints (inputs 5n, outputs n, `hidden`
  /// channels, `levels` blocks of `kernel` taps), the input normalisation folded into block 0 as
  /// tcn_weights_from_file does; prewarmed with the normalisation mean. Throws tpf::Error naming
  /// the file and field when its architecture or a tensor's shape differs.
  void load(const TcnWeightFile& file, int joints, int hidden, int levels, int kernel);

  /// Pushes x(t) and returns τ_TCN(t) = low(t) + high(t) [N·m].
  const Output& step(const Input& x) noexcept;
  /// Prewarms every block's history with the activations of the steady input x̄.
  void reset(const Input& x) noexcept;
  /// R = 1 + (K − 1)·(2^Levels − 1) samples.
  int receptive_field() const noexcept;

 private:
  void apply_heads() noexcept;

  int levels_ = 0, kernel_ = 0;
  std::vector<Eigen::MatrixXd> input_taps_;  ///< [j]: lag j of block 0, normalisation folded in
  Eigen::MatrixXd input_projection_;
  Eigen::VectorXd input_bias_;
  std::vector<std::vector<Eigen::MatrixXd>> taps_;  ///< [l − 1][j], blocks l ≥ 1
  std::vector<Eigen::VectorXd> bias_;               ///< [l − 1]
  Eigen::MatrixXd low_weight_, high_weight_;
  Eigen::VectorXd low_bias_, high_bias_;

  /// Ring of each block's input: [0] the raw inputs (K columns), [l] block l − 1's output
  /// ((K − 1)·2^l + 1 columns); heads_[l] is the column the next input goes to.
  std::vector<Eigen::MatrixXd> history_;
  std::vector<int> heads_;
  Eigen::VectorXd last_input_, hidden_, z_, output_;
};

}  // namespace tpf::offline
