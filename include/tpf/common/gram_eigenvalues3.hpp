// Eigenvalues of the Gram matrix J·Jᵀ of a 3×N matrix, in closed form where J has at most two
// nonzero columns.
#pragma once

#include <algorithm>
#include <cmath>

#include "tpf/common/symmetric_eigenvalues3.hpp"
#include "tpf/common/types.hpp"

namespace tpf {

/// The eigenvalues of a·aᵀ + b·bᵀ (3-vectors a, b), ascending: 0 and those of the 2×2 Gram
/// [a·a a·b; a·b b·b], λ_max = (a·a + b·b)/2 + √(((a·a − b·b)/2)² + (a·b)²) (a sum of
/// non-negative terms) and λ_min = |a×b|²/λ_max (the determinant by Lagrange's identity, without
/// the cancellation of a·a·b·b − (a·b)²). Entries up to ≈ 1e75 (|a×b|² must not overflow).
template <typename S>
Vector3<S> two_column_gram_eigenvalues(const Vector3<S>& a, const Vector3<S>& b) noexcept {
  using std::sqrt;
  const S aa = a.squaredNorm(), bb = b.squaredNorm(), ab = a.dot(b);
  const S half_difference = S(0.5) * (aa - bb);
  const S lambda_max = S(0.5) * (aa + bb) + sqrt(half_difference * half_difference + ab * ab);
  const S determinant = a.cross(b).squaredNorm();
  const S lambda_min = lambda_max > S(0) ? std::min(determinant / lambda_max, lambda_max) : S(0);
  return Vector3<S>(S(0), lambda_min, lambda_max);
}

/// The eigenvalues of G = J·Jᵀ for a 3×N J, ascending, given G too. Where J has at most two
/// nonzero columns — a point Jacobian of a link near the base, whose later joints' columns are
/// zero — its rank is at most two and they come in closed form from those columns
/// (two_column_gram_eigenvalues: ≤ 3 ε·λ_max from a long-double reference, 1.4e-15 relative on
/// λ_min ≥ 4e-4·λ_max; the zero eigenvalue exact, where iterating on G leaves up to ≈ ε·λ_max);
/// otherwise from G by symmetric_eigenvalues3 (≤ 2.5 ε·λ_max)
/// (tests/estimation/gram_eigenvalues3_test.cpp). A non-finite entry gives non-finite
/// eigenvalues. Allocation-free.
template <typename S, int N>
Vector3<S> gram_eigenvalues3(const Eigen::Matrix<S, 3, N>& J, const Matrix3<S>& gram) noexcept {
  Eigen::Index columns[2] = {0, 0};
  int nonzero = 0;
  for (Eigen::Index j = 0; j < J.cols(); ++j) {
    if ((J.col(j).array() == S(0)).all()) continue;  // a NaN column counts as nonzero
    if (nonzero == 2) return symmetric_eigenvalues3(gram);
    columns[nonzero++] = j;
  }
  if (nonzero == 0) return Vector3<S>::Zero();
  const Vector3<S> a = J.col(columns[0]);
  if (nonzero == 1) return Vector3<S>(S(0), S(0), a.squaredNorm());
  return two_column_gram_eigenvalues(a, J.col(columns[1]).eval());
}

}  // namespace tpf
