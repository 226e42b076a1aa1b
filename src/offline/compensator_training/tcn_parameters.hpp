// Run-time-sized TCN parameters for training, and their conversion to and from the weight file.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf::offline {

/// Hyperparameters of the TCN (see tpf::Tcn for the equations). Defaults: 4 inputs (the synthetic
/// friction data's [q, q̇, q̈, τ̂_fric,s]; the compensator's networks take the 5 of
/// compensator_input per joint, set by train_compensator) → 1 output per head, 32 channels,
/// 4 levels, kernel 4
/// (receptive field 46 samples = 115 ms at 400 Hz; 5 levels give 94 samples = 235 ms at
/// ≈ 1.35× the step cost, see docs/tcn.md).
struct TcnArchitecture {
  int inputs = 4;
  int hidden = 32;
  int levels = 4;
  int kernel = 4;
  int outputs = 1;

  /// d_l = 2^l.
  int dilation(int level) const { return 1 << level; }
  /// R = 1 + (K − 1)·(2^levels − 1) samples.
  int receptive_field() const { return 1 + (kernel - 1) * ((1 << levels) - 1); }
  /// Input channels of block l: inputs for l = 0, hidden after.
  int block_inputs(int level) const { return level == 0 ? inputs : hidden; }
};

/// One residual block: z = b + Σ_j taps[j]·x(t − j·d) + P·x(t), y = ReLU(z).
template <typename S>
struct BasicTcnBlockParameters {
  using Matrix = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<S, Eigen::Dynamic, 1>;

  std::vector<Matrix> taps;  ///< taps[j] (C_out × C_in) multiplies the input at lag j·d
  Vector bias;
  Matrix projection;  ///< 1×1 projection P (C_out × C_in); empty when C_in = C_out (P = I)
};

/// All trainable tensors, acting on the normalised input x̃ = (x − mean)/std. Training keeps
/// them in double (TcnParameters) and may evaluate windows in float (cast<float>()).
template <typename S>
struct BasicTcnParameters {
  using Matrix = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
  using Vector = Eigen::Matrix<S, Eigen::Dynamic, 1>;

  TcnArchitecture architecture;
  Eigen::VectorXd input_mean;
  Eigen::VectorXd input_std;
  std::vector<BasicTcnBlockParameters<S>> blocks;
  Matrix low_weight;  ///< Out × Hidden
  Vector low_bias;
  Matrix high_weight;
  Vector high_bias;

  /// The same parameters in scalar T.
  template <typename T>
  BasicTcnParameters<T> cast() const {
    BasicTcnParameters<T> p;
    p.architecture = architecture;
    p.input_mean = input_mean;
    p.input_std = input_std;
    p.blocks.resize(blocks.size());
    for (std::size_t l = 0; l < blocks.size(); ++l) {
      for (const auto& w : blocks[l].taps)
        p.blocks[l].taps.push_back(w.template cast<T>());
      p.blocks[l].bias = blocks[l].bias.template cast<T>();
      p.blocks[l].projection = blocks[l].projection.template cast<T>();
    }
    p.low_weight = low_weight.template cast<T>();
    p.low_bias = low_bias.template cast<T>();
    p.high_weight = high_weight.template cast<T>();
    p.high_bias = high_bias.template cast<T>();
    return p;
  }
};

using TcnBlockParameters = BasicTcnBlockParameters<double>;
using TcnParameters = BasicTcnParameters<double>;

/// Parameters of the right shapes, all zero, normalisation mean 0 and std 1.
TcnParameters zero_tcn_parameters(const TcnArchitecture& architecture);

/// He-uniform initialisation (conv taps ~ U(±√(6/(K·C_in))), projection ~ U(±√(6/C_in))),
/// zero biases, heads ~ U(±√(1/Hidden))·0.1; deterministic by seed.
TcnParameters init_tcn_parameters(const TcnArchitecture& architecture, std::uint64_t seed);

/// Visits every trainable tensor in a fixed order with its weight-file name and its coefficients.
void for_each_tcn_tensor(
    TcnParameters& parameters,
    const std::function<void(const std::string& name, double* values, Eigen::Index size)>& visit);

/// Number of trainable coefficients.
Eigen::Index tcn_parameter_count(const TcnArchitecture& architecture);

/// The trainable coefficients as one vector, in for_each_tcn_tensor order, and back.
Eigen::VectorXd flatten(TcnParameters& parameters);
void unflatten(const Eigen::VectorXd& flat, TcnParameters& parameters);

/// To the weight-file layout (conv [C_out, C_in, K] with k = K − 1 − lag), and back.
TcnWeightFile to_weight_file(const TcnParameters& parameters);
/// Throws tpf::Error (naming file and tensor) if a tensor is missing or has the wrong shape.
TcnParameters from_weight_file(const TcnWeightFile& file);

}  // namespace tpf::offline
