#include "offline/training/training_dataset.hpp"

#include <cmath>

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

std::vector<TcnSequence> onset_sequences(const EstimatorTrace& trace,
                                         const Eigen::VectorXd& effort_per_newton_metre, int joint,
                                         int receptive_field, int outputs, int lead,
                                         double static_velocity) {
  const TcnSequence all = training_sequence(trace, effort_per_newton_metre, joint);
  const Eigen::Index length = receptive_field - 1 + outputs;
  std::vector<TcnSequence> out;
  Eigen::Index last_first = -1;
  for (Eigen::Index k = 1; k < trace.rows(); ++k) {
    bool onset = false;
    for (Eigen::Index j = 0; j < trace.dq.cols(); ++j) {
      if (joint >= 0 && j != joint) continue;
      onset = onset || (std::abs(trace.dq(k - 1, j)) < static_velocity &&
                        std::abs(trace.dq(k, j)) >= static_velocity);
    }
    if (!onset) continue;
    const Eigen::Index first = k - lead - (receptive_field - 1);
    if (first < 0 || first + length > trace.rows() || first < last_first + length / 2) continue;
    TcnSequence s{all.inputs.middleRows(first, length), all.residual.middleRows(first, length)};
    if (!s.inputs.allFinite() || !s.residual.allFinite()) continue;
    out.push_back(std::move(s));
    last_first = first;
  }
  return out;
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
