// The smaller eigenvalue of a symmetric 2×2 matrix in closed form, with the arithmetic of Eigen's
// SelfAdjointEigenSolver::computeDirect, without its solver object.
#pragma once

#include <algorithm>
#include <cmath>

#include "tpf/common/types.hpp"

namespace tpf {

/// The smaller eigenvalue of [a b; b c], the operations of Eigen 3.4's 2×2 computeDirect in its
/// order (so bit for bit its eigenvalues()[0]): shift by the mean s = (a + c)/2, divide by the
/// largest |entry| m of the shifted matrix (when m > 0), λ = (a' + c')/2 − √((a' − c')² + 4b'²)/2
/// on the scaled entries, then λ·m + s. Only the lower triangle's b is read, as Eigen reads it.
template <typename S>
S smaller_symmetric_eigenvalue2(S a, S b, S c) noexcept {
  using std::abs, std::max, std::sqrt;
  const S shift = (a + c) / S(2);
  a -= shift;
  c -= shift;
  const S scale = max(max(abs(a), abs(b)), abs(c));
  if (scale > S(0)) {
    a /= scale;
    b /= scale;
    c /= scale;
  }
  const S half_root = S(0.5) * sqrt((a - c) * (a - c) + S(4) * (b * b));
  const S mean = S(0.5) * (a + c);
  return (mean - half_root) * scale + shift;
}

/// The same for the top-left 2×2 block of a symmetric matrix (lower triangle read).
template <typename S>
S smaller_symmetric_eigenvalue2(const Matrix3<S>& m) noexcept {
  return smaller_symmetric_eigenvalue2(m(0, 0), m(1, 0), m(1, 1));
}

}  // namespace tpf
