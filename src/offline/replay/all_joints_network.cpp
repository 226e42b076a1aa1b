#include "offline/replay/all_joints_network.hpp"

#include <algorithm>
#include <utility>

#include "tpf/estimation/compensator.hpp"
#include "tpf/nn/load_tcn_weights.hpp"

namespace tpf::offline {
namespace {

/// (i + 1) mod n for i in [0, n).
int next_column(int i, int n) noexcept {
  return i + 1 == n ? 0 : i + 1;
}

/// (K − 1)·2^l + 1: ring length of block l's input.
int ring_length(int kernel, int level) noexcept {
  return (kernel - 1) * (1 << level) + 1;
}

}  // namespace

void AllJointsNetwork::load(const TcnWeightFile& file, int joints, int hidden, int levels,
                            int kernel) {
  const int in = kCompensatorInputsPerJoint * joints, out = joints;
  // Everything is checked before anything changes (tcn_weights_from_file's order).
  require_tcn_tensors(file, in, hidden, levels, kernel, out);

  levels_ = levels;
  kernel_ = kernel;
  FoldedInputBlock input = fold_input_block(file, in, hidden, kernel);
  input_taps_ = std::move(input.taps);
  input_projection_ = std::move(input.projection);
  input_bias_ = std::move(input.bias);
  const Eigen::VectorXd mean = Eigen::Map<const Eigen::VectorXd>(file.input_mean.data(), in);

  taps_.assign(static_cast<std::size_t>(levels - 1), {});
  bias_.assign(static_cast<std::size_t>(levels - 1), Eigen::VectorXd());
  for (int l = 1; l < levels; ++l) {
    const TcnTensor& w = file.tensor(tcn_conv_weight_name(l), {hidden, hidden, kernel});
    auto& block = taps_[static_cast<std::size_t>(l - 1)];
    for (int j = 0; j < kernel; ++j)
      block.push_back(tcn_tensor_tap(w, j, kernel));
    bias_[static_cast<std::size_t>(l - 1)] =
        tcn_tensor_vector(file.tensor(tcn_conv_bias_name(l), {hidden}));
  }
  low_weight_ = tcn_tensor_matrix(file.tensor(tcn_head_weight_name(false), {out, hidden}));
  low_bias_ = tcn_tensor_vector(file.tensor(tcn_head_bias_name(false), {out}));
  high_weight_ = tcn_tensor_matrix(file.tensor(tcn_head_weight_name(true), {out, hidden}));
  high_bias_ = tcn_tensor_vector(file.tensor(tcn_head_bias_name(true), {out}));

  history_.assign(static_cast<std::size_t>(levels), Eigen::MatrixXd());
  history_[0] = Eigen::MatrixXd::Zero(in, kernel);
  for (int l = 1; l < levels; ++l)
    history_[static_cast<std::size_t>(l)] = Eigen::MatrixXd::Zero(hidden, ring_length(kernel, l));
  heads_.assign(static_cast<std::size_t>(levels), 0);
  last_input_ = Eigen::VectorXd::Zero(in);
  hidden_ = z_ = Eigen::VectorXd::Zero(hidden);
  output_ = Eigen::VectorXd::Zero(out);
  reset(mean);
}

void AllJointsNetwork::reset(const Input& x) noexcept {
  last_input_ = x;
  history_[0].colwise() = x;
  std::fill(heads_.begin(), heads_.end(), 0);
  hidden_.noalias() = input_bias_ + input_projection_ * x;
  for (int j = 0; j < kernel_; ++j)
    hidden_.noalias() += input_taps_[static_cast<std::size_t>(j)] * x;
  hidden_ = hidden_.cwiseMax(0.0);
  for (int l = 1; l < levels_; ++l) {
    const auto ul = static_cast<std::size_t>(l);
    history_[ul].colwise() = hidden_;
    z_ = bias_[ul - 1] + hidden_;
    for (int j = 0; j < kernel_; ++j)
      z_.noalias() += taps_[ul - 1][static_cast<std::size_t>(j)] * hidden_;
    hidden_ = z_.cwiseMax(0.0);
  }
  apply_heads();
}

const AllJointsNetwork::Output& AllJointsNetwork::step(const Input& x) noexcept {
  if (x.allFinite()) last_input_ = x;
  // Block 0: the raw input's ring has K columns (dilation 1).
  int head = heads_[0];
  history_[0].col(head) = last_input_;
  hidden_.noalias() = input_bias_ + input_projection_ * last_input_;
  for (int j = 0; j < kernel_; ++j) {
    const int column = head - j < 0 ? head - j + kernel_ : head - j;
    hidden_.noalias() += input_taps_[static_cast<std::size_t>(j)] * history_[0].col(column);
  }
  heads_[0] = next_column(head, kernel_);
  hidden_ = hidden_.cwiseMax(0.0);
  for (int l = 1; l < levels_; ++l) {
    const auto ul = static_cast<std::size_t>(l);
    const int length = ring_length(kernel_, l), dilation = 1 << l;
    head = heads_[ul];
    history_[ul].col(head) = hidden_;
    z_ = bias_[ul - 1] + hidden_;
    for (int j = 0; j < kernel_; ++j) {
      const int lagged = head - j * dilation;
      const int column = lagged < 0 ? lagged + length : lagged;
      z_.noalias() += taps_[ul - 1][static_cast<std::size_t>(j)] * history_[ul].col(column);
    }
    heads_[ul] = next_column(head, length);
    hidden_ = z_.cwiseMax(0.0);
  }
  apply_heads();
  return output_;
}

int AllJointsNetwork::receptive_field() const noexcept {
  return 1 + (kernel_ - 1) * ((1 << levels_) - 1);
}

void AllJointsNetwork::apply_heads() noexcept {
  output_.noalias() = low_bias_ + low_weight_ * hidden_;
  output_.noalias() += high_bias_ + high_weight_ * hidden_;
}

}  // namespace tpf::offline
