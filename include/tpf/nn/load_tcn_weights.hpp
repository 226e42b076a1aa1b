// Start-up loading of a TCN weight file into a compiled-size Tcn, folding in the normalisation.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "tpf/nn/tcn.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf {

/// Copies the tensors of `file` into `weights`, folding the input normalisation x̃ = D·(x − μ),
/// D = diag(1/σ), into block 0 (W̃, b̃, P̃ act on x̃; P̃ = I when In == Hidden):
///   W_{0,j} = W̃_{0,j}·D,   P_0 = P̃_0·D,   b_0 = b̃_0 − (Σ_j W̃_{0,j} + P̃_0)·D·μ.
/// The file's kernel index k is the lag j = K − 1 − k. Throws tpf::Error naming the file and the
/// field if an architecture hyperparameter or a tensor shape differs from the compiled sizes, or if
/// a tensor is missing or unknown; `weights` are left unchanged then.
template <typename S, int In, int Hidden, int Levels, int Kernel, int Out>
void tcn_weights_from_file(const TcnWeightFile& file,
                           TcnWeights<S, In, Hidden, Levels, Kernel, Out>& weights) {
  using MatrixXd = Eigen::MatrixXd;
  // Check everything before touching `weights`, so a refused file leaves them unchanged.
  file.require_architecture(In, Hidden, Levels, Kernel, Out);
  std::vector<std::string> names;
  for (int l = 0; l < Levels; ++l) {
    names.push_back(tcn_conv_weight_name(l));
    file.tensor(names.back(), {Hidden, l == 0 ? In : Hidden, Kernel});
    names.push_back(tcn_conv_bias_name(l));
    file.tensor(names.back(), {Hidden});
  }
  if constexpr (In != Hidden) {
    names.push_back(tcn_downsample_name());
    file.tensor(names.back(), {Hidden, In, 1});
  }
  for (bool high : {false, true}) {
    names.push_back(tcn_head_weight_name(high));
    file.tensor(names.back(), {Out, Hidden});
    names.push_back(tcn_head_bias_name(high));
    file.tensor(names.back(), {Out});
  }
  file.refuse_unexpected_tensors(names);

  // Row-major [rows, cols, K] tensor → the rows×cols matrix of lag j.
  auto tap = [](const TcnTensor& t, int j) {
    const int rows = t.shape[0], cols = t.shape[1], k = Kernel - 1 - j;
    MatrixXd m(rows, cols);
    for (int r = 0; r < rows; ++r)
      for (int c = 0; c < cols; ++c)
        m(r, c) = t.values[(r * cols + c) * Kernel + k];
    return m;
  };
  auto matrix = [](const TcnTensor& t) {
    return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
               t.values.data(), t.shape[0], static_cast<Eigen::Index>(t.values.size()) / t.shape[0])
        .eval();
  };
  auto vector = [](const TcnTensor& t) {
    return Eigen::Map<const Eigen::VectorXd>(t.values.data(), t.shape[0]).eval();
  };

  const Eigen::VectorXd mean = Eigen::Map<const Eigen::VectorXd>(file.input_mean.data(), In);
  const Eigen::VectorXd inv_std =
      Eigen::Map<const Eigen::VectorXd>(file.input_std.data(), In).cwiseInverse();

  const TcnTensor& w0 = file.tensor(tcn_conv_weight_name(0), {Hidden, In, Kernel});
  Eigen::VectorXd b0 = vector(file.tensor(tcn_conv_bias_name(0), {Hidden}));
  MatrixXd projection = MatrixXd::Identity(Hidden, In);
  if constexpr (In != Hidden)
    projection = matrix(file.tensor(tcn_downsample_name(), {Hidden, In, 1}));
  MatrixXd sum = projection;
  for (int j = 0; j < Kernel; ++j) {
    const MatrixXd w = tap(w0, j);
    sum += w;
    weights.input_taps[j] = (w * inv_std.asDiagonal()).template cast<S>();
  }
  weights.input_projection = (projection * inv_std.asDiagonal()).template cast<S>();
  weights.input_bias = (b0 - sum * inv_std.asDiagonal() * mean).template cast<S>();

  for (int l = 1; l < Levels; ++l) {
    const TcnTensor& w = file.tensor(tcn_conv_weight_name(l), {Hidden, Hidden, Kernel});
    for (int j = 0; j < Kernel; ++j)
      weights.taps[l - 1][j] = tap(w, j).template cast<S>();
    weights.bias[l - 1] = vector(file.tensor(tcn_conv_bias_name(l), {Hidden})).template cast<S>();
  }
  weights.low_weight =
      matrix(file.tensor(tcn_head_weight_name(false), {Out, Hidden})).template cast<S>();
  weights.low_bias = vector(file.tensor(tcn_head_bias_name(false), {Out})).template cast<S>();
  weights.high_weight =
      matrix(file.tensor(tcn_head_weight_name(true), {Out, Hidden})).template cast<S>();
  weights.high_bias = vector(file.tensor(tcn_head_bias_name(true), {Out})).template cast<S>();
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
