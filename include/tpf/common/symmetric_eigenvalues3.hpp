// Eigenvalues of a symmetric 3×3 matrix by cyclic Jacobi rotations, written out.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "tpf/common/types.hpp"

namespace tpf {

/// |x| = |a_pq/(a_qq − a_pp)| up to which small_rotation is exact to rounding in double.
inline constexpr double kSeriesLimit = 0.01;

/// A plane rotation by θ: t = tan θ, c = cos θ, s = sin θ.
template <typename S>
struct PlaneRotation {
  S t, c, s;
};

/// The Jacobi rotation of a small angle without square roots, for tan 2θ = 2x, |x| ≤ kSeriesLimit:
/// t, c and s each a series in z = x² (Catalan numbers for t = x(1 − z + 2z² − 5z³ + 14z⁴);
/// c = 1 − z/2 + 11z²/8 − 69z³/16 + 1843z⁴/128, s = x(1 − 3z/2 + 31z²/8 − 187z³/16 + 4859z⁴/128)),
/// evaluated side by side in Estrin's form, so that s and c wait on one division and ≈ 3
/// multiply-adds, not on t; the first terms left out (42z⁵, …) are below 2e-18 relative. After
/// the first sweep most rotations are this small.
template <typename S>
PlaneRotation<S> small_rotation(S x) noexcept {
  const S z = x * x, z2 = z * z;
  return {x * ((S(1) - z) + z2 * ((S(2) + z * S(-5)) + z2 * S(14))),
          (S(1) + z * S(-0.5)) + z2 * ((S(1.375) + z * S(-4.3125)) + z2 * S(14.3984375)),
          x * ((S(1) + z * S(-1.5)) + z2 * ((S(3.875) + z * S(-11.6875)) + z2 * S(37.9609375)))};
}

/// The Jacobi rotation that zeroes a_pq (≠ 0) given d = a_qq − a_pp: tan θ = t, the smaller root of
/// t² + 2τt − 1 = 0, τ = d/(2a_pq), i.e. t = 2a_pq/w with w = d + sgn(d)·√(d² + 4a_pq²); then
/// c = |w|/√(w² + 4a_pq²) = |w|/√(2√(d² + 4a_pq²)·|w|) and s = sgn(d)·2a_pq/√(…), so that c and s
/// do not wait on t. Small angles by small_rotation.
template <typename S>
PlaneRotation<S> jacobi_rotation(S difference, S apq) noexcept {
  using std::abs, std::sqrt;
  if (abs(apq) <= S(kSeriesLimit) * abs(difference)) return small_rotation(apq / difference);
  const S root = sqrt(difference * difference + S(4) * apq * apq);
  const S w = difference >= S(0) ? difference + root : difference - root;  // |w| ≥ root > 0
  const S inverse = S(1) / sqrt(S(2) * root * abs(w));                     // 1/√(w² + 4a_pq²)
  return {S(2) * apq / w, abs(w) * inverse,
          (difference >= S(0) ? S(2) * apq : S(-2) * apq) * inverse};
}

/// The eigenvalues of a symmetric 3×3 A (its upper triangle is read), ascending. Cyclic Jacobi:
/// each rotation zeroes one off-diagonal entry a_pq (jacobi_rotation), sweeps (0,1), (0,2), (1,2)
/// until every off-diagonal entry is zero or negligible against its diagonal pair (a_pq² ≤
/// (ε/16)²·|a_pp·a_qq|, the relative criterion: a positive semidefinite matrix keeps its small
/// eigenvalues to about ε·λ_max absolute, as Eigen's QR iteration does and better), at most 10
/// sweeps (3 or 4 in practice: the convergence is quadratic). Against a long-double reference on
/// Gram matrices J·Jᵀ and clustered spectra the error is ≤ 2.5 ε·λ_max (Eigen's
/// SelfAdjointEigenSolver: ≤ 9 ε·λ_max), ≤ 4e-13 relative on λ_min ≥ 4e-4·λ_max, the contact
/// force's rank threshold (tests/estimation/symmetric_eigenvalues3_test.cpp). Entries up to ≈ 1e150
/// (a squared difference must not overflow); a non-finite entry gives non-finite eigenvalues.
/// Allocation-free; rotations of a small angle (most after the first sweep) take no square root
/// (small_rotation). Cheaper than Eigen's solver for eigenvalues only (docs/performance.md).
template <typename S>
Vector3<S> symmetric_eigenvalues3(const Matrix3<S>& a) noexcept {
  using std::abs;
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
    const auto [t, c, s] = jacobi_rotation(aqq - app, apq);
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
