// Whether every coefficient of some vectors is finite, in a few inlined instructions.
#pragma once

#include <Eigen/Core>

namespace tpf {

/// True when every coefficient of every argument is finite (no NaN, no ±inf): x·0 is ±0 for a
/// finite x and NaN otherwise, and a sum with a NaN in it is NaN, the one value unequal to itself.
/// The same answer as Eigen's allFinite(), which GCC leaves as a call per vector on the per-cycle
/// path. Branch-free, allocation-free.
template <typename First, typename... Rest>
[[gnu::always_inline]] inline bool all_finite(const Eigen::DenseBase<First>& first,
                                              const Eigen::DenseBase<Rest>&... rest) noexcept {
  using S = typename First::Scalar;
  S sum = S(0);
  const auto add = [&sum](const auto& x) {
    for (Eigen::Index i = 0; i < x.size(); ++i)
      sum += x.coeff(i) * S(0);
  };
  add(first.derived());
  (add(rest.derived()), ...);
  return sum == sum;
}

}  // namespace tpf
