#include "offline/samples/sample_regressors.hpp"

#include <algorithm>
#include <utility>

#include "offline/fit/parallel_halves.hpp"
#include "tpf/dynamics/regressor.hpp"

namespace tpf::offline {
namespace {

/// Whether compute_regressor can write a non-zero to Y(row, column) of an N-joint arm.
bool structurally_nonzero(const ModelX& model, int row, int column) {
  const int joints = model.joint_count();
  if (column < 10 * joints) return row <= column / 10;  // link column/10 + 1 moves joints ≤ it
  const int motor = (column - 10 * joints) % joints;    // armature and friction: motor's joints
  return model.coupled ? model.coupling(motor, row) != 0.0 : row == motor;
}

}  // namespace

SampleRegressors::SampleRegressors(const ModelX& model, std::vector<int> columns,
                                   const JointSamples& s)
    : columns_(std::move(columns)) {
  const int joints = model.joint_count();
  std::sort(columns_.begin(), columns_.end());
  columns_.erase(std::unique(columns_.begin(), columns_.end()), columns_.end());
  for (int column : columns_)
    for (int row = 0; row < joints; ++row)
      if (structurally_nonzero(model, row, column)) entries_.push_back({row, column});

  values_.resize(static_cast<Eigen::Index>(entries_.size()), s.size());
  parallel_halves(s.size(), [&](Eigen::Index begin, Eigen::Index end) {
    DataX data(model);
    Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(joints, 13 * joints);
    Eigen::VectorXd q(joints), dq(joints), ddq(joints);  // sized once: assigned per sample
    for (Eigen::Index k = begin; k < end; ++k) {
      if (!s.valid[k]) continue;
      q = s.q.row(k).transpose();
      dq = s.dq.row(k).transpose();
      ddq = s.ddq.row(k).transpose();
      compute_regressor(model, data, q, dq, ddq, Y);
      double* out = values_.col(k).data();
      for (const Entry& e : entries_)
        *out++ = Y(e.row, e.column);
    }
  });
}

bool SampleRegressors::holds(int column) const {
  return std::binary_search(columns_.begin(), columns_.end(), column);
}

void SampleRegressors::load(Eigen::Index k, Eigen::MatrixXd& Y) const {
  const double* in = values_.col(k).data();
  for (const Entry& e : entries_)
    Y(e.row, e.column) = *in++;
}

}  // namespace tpf::offline
