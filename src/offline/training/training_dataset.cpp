#include "offline/training/training_dataset.hpp"

#include "tpf/common/error.hpp"

namespace tpf::offline {

TcnSequence training_sequence(const EstimatorTrace& trace,
                              const Eigen::VectorXd& effort_per_newton_metre, int joint) {
  const Eigen::Index n = trace.residual.cols();
  if (trace.inputs.cols() != 4 * n || effort_per_newton_metre.size() != n || joint >= n)
    throw Error::at("estimator trace", 0, "columns",
                    "inputs, residual and effort scale sizes disagree");
  TcnSequence s;
  if (joint < 0) {
    s.inputs = trace.inputs;
    s.residual = trace.residual * effort_per_newton_metre.cwiseInverse().asDiagonal();
    return s;
  }
  s.inputs.resize(trace.rows(), 4);
  for (int c = 0; c < 4; ++c)
    s.inputs.col(c) = trace.inputs.col(c * n + joint);
  s.residual = trace.residual.col(joint) / effort_per_newton_metre[joint];
  return s;
}

void scale_tcn_outputs(TcnParameters& p, const Eigen::VectorXd& scale) {
  if (scale.size() != p.low_weight.rows())
    throw Error::at("tcn parameters", 0, "outputs", "scale has the wrong size");
  p.low_weight = scale.asDiagonal() * p.low_weight;
  p.high_weight = scale.asDiagonal() * p.high_weight;
  p.low_bias = p.low_bias.cwiseProduct(scale);
  p.high_bias = p.high_bias.cwiseProduct(scale);
}

}  // namespace tpf::offline
