// 3-vector products of the per-joint recursions, written out and always inlined.
#pragma once

#include "tpf/common/types.hpp"

namespace tpf::detail {

// Eigen's fixed 3×3 and 3-vector expressions are not vectorised (3 is no multiple of the packet),
// and GCC outlines their assignment loops once a function uses them often enough; these forms give
// the compiler the scalar expressions, always inlined. The same sums in the same order as Eigen's
// lazy products (coefficient i = Σ_j in j = 0, 1, 2 order). Used where they measured faster (the
// gravity pass: 80 → 67 ns on the 4-DoF arm); in the Newton–Euler passes Eigen's own forms were
// faster, so those keep them (docs/performance.md).

/// R·x.
template <typename S>
[[gnu::always_inline]] inline Vector3<S> rotate(const Matrix3<S>& R, const Vector3<S>& x) noexcept {
  return Vector3<S>(R(0, 0) * x[0] + R(0, 1) * x[1] + R(0, 2) * x[2],
                    R(1, 0) * x[0] + R(1, 1) * x[1] + R(1, 2) * x[2],
                    R(2, 0) * x[0] + R(2, 1) * x[1] + R(2, 2) * x[2]);
}

/// Rᵀ·x.
template <typename S>
[[gnu::always_inline]] inline Vector3<S> rotate_back(const Matrix3<S>& R,
                                                     const Vector3<S>& x) noexcept {
  return Vector3<S>(R(0, 0) * x[0] + R(1, 0) * x[1] + R(2, 0) * x[2],
                    R(0, 1) * x[0] + R(1, 1) * x[1] + R(2, 1) * x[2],
                    R(0, 2) * x[0] + R(1, 2) * x[1] + R(2, 2) * x[2]);
}

/// a × b.
template <typename S>
[[gnu::always_inline]] inline Vector3<S> cross(const Vector3<S>& a, const Vector3<S>& b) noexcept {
  return Vector3<S>(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0]);
}

/// a·b.
template <typename S>
[[gnu::always_inline]] inline S dot(const Vector3<S>& a, const Vector3<S>& b) noexcept {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace tpf::detail
