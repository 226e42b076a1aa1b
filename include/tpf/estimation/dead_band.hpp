// The dead band applied to every external-torque estimate.
#pragma once

#include <cmath>

#include "tpf/common/types.hpp"

namespace tpf {

/// Soft dead band of half-width w ≥ 0: d(x) = sgn(x)·max(|x| − w, 0). Continuous, so an estimate
/// leaves zero smoothly once the residual exceeds the noise band.
template <typename S>
S dead_band(S x, S width) noexcept {
  using std::abs;
  const S excess = abs(x) - width;
  return excess > S(0) ? (x > S(0) ? excess : -excess) : S(0);
}

/// Element-wise dead_band with one width per joint (allocates the result at Eigen::Dynamic).
template <typename S, int N>
JointVector<S, N> dead_band(const JointVector<S, N>& x,
                            const JointVector<S, N>& width) noexcept(N != Eigen::Dynamic) {
  JointVector<S, N> y;
  y.resize(x.size());
  for (int j = 0; j < x.size(); ++j)
    y[j] = dead_band(x[j], width[j]);
  return y;
}

}  // namespace tpf
