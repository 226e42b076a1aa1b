#include "offline/identify/sample_regressors.hpp"

#include <algorithm>
#include <utility>

#include "offline/identify/parallel_halves.hpp"

namespace tpf::offline {
namespace {

/// Whether compute_regressor can write a non-zero to Y(row, column) of an N-joint arm.
bool structurally_nonzero(int joints, int row, int column) {
  if (column < 10 * joints) return row <= column / 10;  // link column/10 + 1 moves joints ≤ it
  return row == (column - 10 * joints) % joints;        // armature and friction: own joint only
}

}  // namespace

template <int N>
SampleRegressors<N>::SampleRegressors(const Model<double, N>& model, std::vector<int> columns,
                                      const JointSamples& s)
    : columns_(std::move(columns)) {
  std::sort(columns_.begin(), columns_.end());
  columns_.erase(std::unique(columns_.begin(), columns_.end()), columns_.end());
  for (int column : columns_)
    for (int row = 0; row < N; ++row)
      if (structurally_nonzero(N, row, column)) entries_.push_back({row, column});

  values_.resize(static_cast<Eigen::Index>(entries_.size()), s.size());
  parallel_halves(s.size(), [&](Eigen::Index begin, Eigen::Index end) {
    Data<double, N> data;
    Regressor<double, N> Y;
    for (Eigen::Index k = begin; k < end; ++k) {
      if (!s.valid[k]) continue;
      compute_regressor(model, data, s.q.row(k).transpose(), s.dq.row(k).transpose(),
                        s.ddq.row(k).transpose(), Y);
      double* out = values_.col(k).data();
      for (const Entry& e : entries_)
        *out++ = Y(e.row, e.column);
    }
  });
}

template <int N>
bool SampleRegressors<N>::holds(int column) const {
  return std::binary_search(columns_.begin(), columns_.end(), column);
}

template <int N>
void SampleRegressors<N>::load(Eigen::Index k, Regressor<double, N>& Y) const {
  const double* in = values_.col(k).data();
  for (const Entry& e : entries_)
    Y(e.row, e.column) = *in++;
}

template class SampleRegressors<1>;
template class SampleRegressors<2>;
template class SampleRegressors<3>;
template class SampleRegressors<4>;
template class SampleRegressors<5>;
template class SampleRegressors<6>;
template class SampleRegressors<7>;

}  // namespace tpf::offline
