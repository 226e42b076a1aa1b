// Shared helpers of the TCN tests: random parameters and a naive full-window reference network.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

#include "offline/compensator_training/tcn_parameters.hpp"
#include "tpf/nn/load_tcn_weights.hpp"

namespace tpf::test {

/// Parameters with every coefficient random (biases and normalisation included).
inline offline::TcnParameters random_tcn_parameters(const offline::TcnArchitecture& a,
                                                    std::uint64_t seed) {
  offline::TcnParameters p = offline::init_tcn_parameters(a, seed);
  std::mt19937_64 rng(seed + 1);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (auto& b : p.blocks)
    for (Eigen::Index i = 0; i < b.bias.size(); ++i)
      b.bias[i] = u(rng);
  for (Eigen::Index i = 0; i < p.low_weight.size(); ++i)
    p.low_weight.data()[i] = 3 * u(rng);
  for (Eigen::Index i = 0; i < p.high_weight.size(); ++i)
    p.high_weight.data()[i] = 3 * u(rng);
  for (Eigen::Index i = 0; i < p.low_bias.size(); ++i)
    p.low_bias[i] = u(rng);
  for (Eigen::Index i = 0; i < p.high_bias.size(); ++i)
    p.high_bias[i] = u(rng);
  for (Eigen::Index i = 0; i < a.inputs; ++i) {
    p.input_mean[i] = 2 * u(rng);
    p.input_std[i] = 0.5 + std::abs(u(rng));
  }
  return p;
}

/// Random raw inputs, In × T (column = time).
inline Eigen::MatrixXd random_inputs(int inputs, Eigen::Index steps, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd x(inputs, steps);
  for (Eigen::Index i = 0; i < x.size(); ++i)
    x.data()[i] = n(rng);
  return x;
}

/// Naive reference: every block evaluated by explicit loops over the whole raw sequence (In × T),
/// valid convolutions only; returns [low; high] ((2·Out) × (T − R + 1)).
inline Eigen::MatrixXd naive_tcn(const offline::TcnParameters& p, const Eigen::MatrixXd& raw) {
  const offline::TcnArchitecture& a = p.architecture;
  Eigen::MatrixXd x(raw.rows(), raw.cols());
  for (Eigen::Index t = 0; t < raw.cols(); ++t)
    for (Eigen::Index c = 0; c < raw.rows(); ++c)
      x(c, t) = (raw(c, t) - p.input_mean[c]) / p.input_std[c];
  for (int l = 0; l < a.levels; ++l) {
    const auto& b = p.blocks[l];
    const int d = a.dilation(l);
    const Eigen::Index span = (a.kernel - 1) * d;
    Eigen::MatrixXd y(a.hidden, x.cols() - span);
    for (Eigen::Index t = span; t < x.cols(); ++t) {
      for (int o = 0; o < a.hidden; ++o) {
        double z = b.bias[o];
        for (Eigen::Index i = 0; i < x.rows(); ++i) {
          for (int j = 0; j < a.kernel; ++j)
            z += b.taps[j](o, i) * x(i, t - j * d);
          z += b.projection.size() > 0 ? b.projection(o, i) * x(i, t) : (i == o ? x(i, t) : 0.0);
        }
        y(o, t - span) = z > 0.0 ? z : 0.0;
      }
    }
    x = y;
  }
  Eigen::MatrixXd out(2 * a.outputs, x.cols());
  out.topRows(a.outputs) = (p.low_weight * x).colwise() + p.low_bias;
  out.bottomRows(a.outputs) = (p.high_weight * x).colwise() + p.high_bias;
  return out;
}

/// Loads trained-side parameters into a compiled-size engine through the weight-file layout.
template <typename Engine>
void load_parameters(const offline::TcnParameters& p, Engine& tcn) {
  TcnWeightFile file = offline::to_weight_file(p);
  file.path = "<memory>";
  tcn_weights_from_file(file, tcn);
}

}  // namespace tpf::test
