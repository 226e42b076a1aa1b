#include "offline/compensator_training/training_dataset.hpp"

#include <cmath>

#include "tpf/common/error.hpp"

namespace tpf::offline {

TcnSequence training_sequence(const EstimatorTrace& trace, int joint) {
  const Eigen::Index n = trace.residual.cols();
  constexpr int channels = kCompensatorInputsPerJoint;
  if (trace.inputs.cols() != channels * n || joint >= n)
    throw Error::at("estimator trace", 0, "columns", "inputs and residual sizes disagree");
  TcnSequence s;
  if (joint < 0) {
    s.inputs = trace.inputs;
    s.residual = trace.residual;
    return s;
  }
  s.inputs.resize(trace.rows(), channels);
  for (int c = 0; c < channels; ++c)
    s.inputs.col(c) = trace.inputs.col(c * n + joint);
  s.residual = trace.residual.col(joint);
  return s;
}

Eigen::MatrixXd regime_weights(const EstimatorTrace& trace, int joint, double static_weight,
                               double static_to_kinetic_weight, const RegimeOptions& regimes) {
  const Eigen::Index n = trace.dq.cols();
  if (joint >= n || trace.t.size() != trace.dq.rows())
    throw Error::at("estimator trace", 0, "columns", "joint or row counts disagree");
  const int first = joint < 0 ? 0 : joint;
  const int count = joint < 0 ? static_cast<int>(n) : 1;
  Eigen::MatrixXd w = Eigen::MatrixXd::Ones(trace.rows(), count);
  for (int c = 0; c < count; ++c) {
    const std::vector<Regime> labels = label_regimes(trace.t, trace.dq.col(first + c), regimes);
    for (Eigen::Index k = 0; k < trace.rows(); ++k) {
      const Regime g = labels[static_cast<std::size_t>(k)];
      if (g == Regime::StaticToKinetic) w(k, c) = static_to_kinetic_weight;
      if (g == Regime::Static) w(k, c) = static_weight;
    }
  }
  return w;
}

void scale_tcn_outputs(TcnParameters& p, const Eigen::VectorXd& scale) {
  if (scale.size() != p.low_weight.rows())
    throw Error::at("tcn parameters", 0, "outputs", "scale has the wrong size");
  p.low_weight = scale.asDiagonal() * p.low_weight;
  p.high_weight = scale.asDiagonal() * p.high_weight;
  p.low_bias = p.low_bias.cwiseProduct(scale);
  p.high_bias = p.high_bias.cwiseProduct(scale);
}

void mask_tcn_inputs(TcnParameters& p, const std::vector<int>& channels) {
  for (int c : channels) {
    if (c < 0 || c >= p.architecture.inputs || p.blocks.empty())
      throw Error::at("tcn parameters", 0, "inputs",
                      "masked channel " + std::to_string(c) + " out of range");
    TcnBlockParameters& first = p.blocks.front();
    if (first.projection.size() == 0)
      throw Error::at("tcn parameters", 0, "inputs",
                      "cannot mask an input of a network without an input projection");
    for (auto& w : first.taps)
      w.col(c).setZero();
    first.projection.col(c).setZero();
    p.input_mean[c] = 0.0;
    p.input_std[c] = 1.0;
  }
}

}  // namespace tpf::offline
