// Start-up loading of a TCN weight file into a compiled-size Tcn, folding in the normalisation.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "tpf/nn/tcn.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf {

/// Lag j of a row-major [rows, cols, K] convolution tensor (file index k = K − 1 − j).
inline Eigen::MatrixXd tcn_tensor_tap(const TcnTensor& t, int j, int kernel) {
  const int rows = t.shape[0], cols = t.shape[1], k = kernel - 1 - j;
  Eigen::MatrixXd m(rows, cols);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      m(r, c) = t.values[static_cast<std::size_t>((r * cols + c) * kernel + k)];
  return m;
}

/// A row-major [rows, cols] tensor as a matrix.
inline Eigen::MatrixXd tcn_tensor_matrix(const TcnTensor& t) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      t.values.data(), t.shape[0], static_cast<Eigen::Index>(t.values.size()) / t.shape[0]);
}

/// A [rows] tensor as a vector.
inline Eigen::VectorXd tcn_tensor_vector(const TcnTensor& t) {
  return Eigen::Map<const Eigen::VectorXd>(t.values.data(), t.shape[0]);
}

/// Checks the architecture and every tensor's shape of a network of `in` inputs, `hidden`
/// channels, `levels` blocks of `kernel` taps and `out` outputs, and refuses a tensor it does not
/// name: everything a loader checks before it changes anything. Throws tpf::Error naming the file
/// and the field.
inline void require_tcn_tensors(const TcnWeightFile& file, int in, int hidden, int levels,
                                int kernel, int out) {
  file.require_architecture(in, hidden, levels, kernel, out);
  std::vector<std::string> names;
  for (int l = 0; l < levels; ++l) {
    names.push_back(tcn_conv_weight_name(l));
    file.tensor(names.back(), {hidden, l == 0 ? in : hidden, kernel});
    names.push_back(tcn_conv_bias_name(l));
    file.tensor(names.back(), {hidden});
  }
  if (in != hidden) {
    names.push_back(tcn_downsample_name());
    file.tensor(names.back(), {hidden, in, 1});
  }
  for (bool high : {false, true}) {
    names.push_back(tcn_head_weight_name(high));
    file.tensor(names.back(), {out, hidden});
    names.push_back(tcn_head_bias_name(high));
    file.tensor(names.back(), {out});
  }
  file.refuse_unexpected_tensors(names);
}

/// Block 0 of a network with the input normalisation x̃ = D·(x − μ), D = diag(1/σ), folded in
/// (tcn_weights_from_file): the taps W_{0,j}, the projection P_0 and the bias b_0.
struct FoldedInputBlock {
  std::vector<Eigen::MatrixXd> taps;
  Eigen::MatrixXd projection;
  Eigen::VectorXd bias;
};

/// Block 0 of `file` (checked by require_tcn_tensors) with the normalisation folded in.
inline FoldedInputBlock fold_input_block(const TcnWeightFile& file, int in, int hidden,
                                         int kernel) {
  const Eigen::VectorXd mean = Eigen::Map<const Eigen::VectorXd>(file.input_mean.data(), in);
  const Eigen::VectorXd inv_std =
      Eigen::Map<const Eigen::VectorXd>(file.input_std.data(), in).cwiseInverse();
  const TcnTensor& w0 = file.tensor(tcn_conv_weight_name(0), {hidden, in, kernel});
  const Eigen::VectorXd b0 = tcn_tensor_vector(file.tensor(tcn_conv_bias_name(0), {hidden}));
  Eigen::MatrixXd projection = Eigen::MatrixXd::Identity(hidden, in);
  if (in != hidden)
    projection = tcn_tensor_matrix(file.tensor(tcn_downsample_name(), {hidden, in, 1}));
  FoldedInputBlock block;
  Eigen::MatrixXd sum = projection;
  for (int j = 0; j < kernel; ++j) {
    const Eigen::MatrixXd w = tcn_tensor_tap(w0, j, kernel);
    sum += w;
    block.taps.push_back(w * inv_std.asDiagonal());
  }
  block.projection = projection * inv_std.asDiagonal();
  block.bias = b0 - sum * inv_std.asDiagonal() * mean;
  return block;
}

/// Copies the tensors of `file` into `weights`, folding the input normalisation x̃ = D·(x − μ),
/// D = diag(1/σ), into block 0 (W̃, b̃, P̃ act on x̃; P̃ = I when In == Hidden):
///   W_{0,j} = W̃_{0,j}·D,   P_0 = P̃_0·D,   b_0 = b̃_0 − (Σ_j W̃_{0,j} + P̃_0)·D·μ.
/// The file's kernel index k is the lag j = K − 1 − k. Throws tpf::Error naming the file and the
/// field if an architecture hyperparameter or a tensor shape differs from the compiled sizes, or if
/// a tensor is missing or unknown; `weights` are left unchanged then.
template <typename S, int In, int Hidden, int Levels, int Kernel, int Out>
void tcn_weights_from_file(const TcnWeightFile& file,
                           TcnWeights<S, In, Hidden, Levels, Kernel, Out>& weights) {
  // Check everything before touching `weights`, so a refused file leaves them unchanged.
  require_tcn_tensors(file, In, Hidden, Levels, Kernel, Out);
  const FoldedInputBlock input = fold_input_block(file, In, Hidden, Kernel);
  for (int j = 0; j < Kernel; ++j)
    weights.input_taps[j] = input.taps[static_cast<std::size_t>(j)].template cast<S>();
  weights.input_projection = input.projection.template cast<S>();
  weights.input_bias = input.bias.template cast<S>();

  for (int l = 1; l < Levels; ++l) {
    const TcnTensor& w = file.tensor(tcn_conv_weight_name(l), {Hidden, Hidden, Kernel});
    for (int j = 0; j < Kernel; ++j)
      weights.taps[l - 1][j] = tcn_tensor_tap(w, j, Kernel).template cast<S>();
    weights.bias[l - 1] =
        tcn_tensor_vector(file.tensor(tcn_conv_bias_name(l), {Hidden})).template cast<S>();
  }
  weights.low_weight =
      tcn_tensor_matrix(file.tensor(tcn_head_weight_name(false), {Out, Hidden})).template cast<S>();
  weights.low_bias =
      tcn_tensor_vector(file.tensor(tcn_head_bias_name(false), {Out})).template cast<S>();
  weights.high_weight =
      tcn_tensor_matrix(file.tensor(tcn_head_weight_name(true), {Out, Hidden})).template cast<S>();
  weights.high_bias =
      tcn_tensor_vector(file.tensor(tcn_head_bias_name(true), {Out})).template cast<S>();
}

/// The same into the network `tcn` (Tcn::set_weights: its history is cleared), through a heap
/// copy of the weights (a 64-channel double network's are ≈ 650 kB). Start-up only.
template <typename S, int In, int Hidden, int Levels, int Kernel, int Out, typename H>
void tcn_weights_from_file(const TcnWeightFile& file,
                           Tcn<S, In, Hidden, Levels, Kernel, Out, H>& tcn) {
  auto weights = std::make_unique<TcnWeights<S, In, Hidden, Levels, Kernel, Out>>();
  tcn_weights_from_file(file, *weights);
  tcn.set_weights(*weights);
}

/// Loads the weight file at `path` into `tcn` (start-up only: allocates, may throw tpf::Error)
/// and prewarms it with the normalisation mean as steady input; call tcn.reset(x̄) with the real
/// first sample before streaming.
template <typename S, int In, int Hidden, int Levels, int Kernel, int Out, typename H>
void load_tcn_weights(const std::string& path, Tcn<S, In, Hidden, Levels, Kernel, Out, H>& tcn) {
  const TcnWeightFile file = read_tcn_weight_file(path);
  tcn_weights_from_file(file, tcn);
  tcn.reset(Eigen::Map<const Eigen::VectorXd>(file.input_mean.data(), In).template cast<S>());
}

}  // namespace tpf
