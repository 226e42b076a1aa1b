// Eigenvalues of a symmetric 3×3 matrix by cyclic Jacobi rotations, written out.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "tpf/common/types.hpp"

namespace tpf {

/// |x| = |a_pq/(a_qq − a_pp)| up to which small_rotation is exact to rounding in double.
inline constexpr double kSeriesLimit = 0.01;

/// The Jacobi rotation of a small angle without square roots: t = tan θ and c = cos θ for
/// tan 2θ = 2x, |x| ≤ kSeriesLimit, by their series t = x(1 − x² + 2x⁴ − 5x⁶ + 14x⁸)
/// (Catalan numbers) and c = (1 + t²)^(−1/2) = 1 − u/2 + 3u²/8 − 5u³/16, u = t²: the first
/// terms left out (42x¹⁰, 35u⁴/128) are below 3e-17 relative. After the first sweep most rotations
/// are this small.
template <typename S>
void small_rotation(S x, S& t, S& c) noexcept {
  const S z = x * x;
  t = x * (S(1) + z * (S(-1) + z * (S(2) + z * (S(-5) + z * S(14)))));
  const S u = t * t;
  c = S(1) + u * (S(-0.5) + u * (S(0.375) + u * S(-0.3125)));
}

/// The eigenvalues of a symmetric 3×3 A (its upper triangle is read), ascending. Cyclic Jacobi:
/// each rotation zeroes one off-diagonal entry a_pq (tan θ = t, the smaller root of
/// t² + 2τt − 1 = 0, τ = (a_qq − a_pp)/(2a_pq)), sweeps (0,1), (0,2), (1,2) until every
/// off-diagonal entry is zero or negligible against its diagonal pair (a_pq² ≤ (ε/16)²·|a_pp·a_qq|,
/// the relative criterion: a positive semidefinite matrix keeps its small eigenvalues to about
/// ε·λ_max absolute, as Eigen's QR iteration does and better), at most 10 sweeps (3 or 4 in
/// practice: the convergence is quadratic). Against a long-double reference on Gram matrices
/// J·Jᵀ and clustered spectra the error is ≤ 2.2 ε·λ_max (Eigen's SelfAdjointEigenSolver:
/// ≤ 9 ε·λ_max), ≤ 3e-13 relative on λ_min ≥ 4e-4·λ_max, the contact force's rank threshold
/// (tests/estimation/symmetric_eigenvalues3_test.cpp).
/// Entries up to ≈ 1e150 (a squared difference must not overflow); a non-finite entry gives
/// non-finite eigenvalues. Allocation-free; rotations of a small angle (most after the first sweep)
/// take no square root (small_rotation). Cheaper than Eigen's solver for eigenvalues
/// only (docs/performance.md).
template <typename S>
Vector3<S> symmetric_eigenvalues3(const Matrix3<S>& a) noexcept {
  using std::abs, std::sqrt;
  constexpr S tiny =
      (std::numeric_limits<S>::epsilon() / 16) * (std::numeric_limits<S>::epsilon() / 16);
  S d0 = a(0, 0), d1 = a(1, 1), d2 = a(2, 2);
  S o01 = a(0, 1), o02 = a(0, 2), o12 = a(1, 2);
  // Zeroes a_pq of the pair (p, q); r is the third index, a_rp and a_rq turn with the pair.
  const auto rotate = [](S& app, S& aqq, S& apq, S& arp, S& arq) noexcept {
    if (apq * apq <= tiny * abs(app * aqq)) {  // false for NaN: it then reaches the diagonal
      apq = S(0);
      return;
    }
    const S difference = aqq - app;
    S t, c, s;
    if (abs(apq) <= S(kSeriesLimit) * abs(difference)) {
      small_rotation(apq / difference, t, c);
      s = t * c;
    } else {
      const S root = sqrt(difference * difference + S(4) * apq * apq);
      t = S(2) * apq / (difference >= S(0) ? difference + root : difference - root);
      c = S(1) / sqrt(S(1) + t * t);
      s = t * c;
    }
    app -= t * apq;
    aqq += t * apq;
    apq = S(0);
    const S rp = arp, rq = arq;
    arp = c * rp - s * rq;
    arq = s * rp + c * rq;
  };
  for (int sweep = 0; sweep < 10 && !(o01 == S(0) && o02 == S(0) && o12 == S(0)); ++sweep) {
    rotate(d0, d1, o01, o02, o12);
    rotate(d0, d2, o02, o01, o12);
    rotate(d1, d2, o12, o01, o02);
  }
  Vector3<S> lambda(d0, d1, d2);
  if (lambda[0] > lambda[1]) std::swap(lambda[0], lambda[1]);
  if (lambda[1] > lambda[2]) std::swap(lambda[1], lambda[2]);
  if (lambda[0] > lambda[1]) std::swap(lambda[0], lambda[1]);
  return lambda;
}

}  // namespace tpf
