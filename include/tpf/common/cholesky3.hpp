// Cholesky factorisation of a symmetric positive definite 3×3 matrix, written out: the solve and
// the diagonal of the inverse without Eigen's general (dynamic-size) triangular-solve kernels.
#pragma once

#include <cmath>

#include "tpf/common/types.hpp"

namespace tpf {

/// A = L·Lᵀ for a symmetric positive definite A (only its lower triangle is read); keeps L⁻¹,
/// from which A⁻¹·b = L⁻ᵀ(L⁻¹·b) and diag(A⁻¹)_i = Σ_{k ≥ i} (L⁻¹)_{ki}². On a matrix that is not
/// positive definite the results are not finite (a pivot's square root of a non-positive number).
template <typename S>
class Cholesky3 {
 public:
  explicit Cholesky3(const Matrix3<S>& a) noexcept {
    using std::sqrt;
    const S l00 = sqrt(a(0, 0));
    const S l10 = a(1, 0) / l00, l20 = a(2, 0) / l00;
    const S l11 = sqrt(a(1, 1) - l10 * l10);
    const S l21 = (a(2, 1) - l20 * l10) / l11;
    const S l22 = sqrt(a(2, 2) - l20 * l20 - l21 * l21);
    // L⁻¹, lower triangular: forward substitution on the identity's columns.
    i00_ = S(1) / l00;
    i11_ = S(1) / l11;
    i22_ = S(1) / l22;
    i10_ = -l10 * i00_ * i11_;
    i21_ = -l21 * i11_ * i22_;
    i20_ = -(l20 * i00_ + l21 * i10_) * i22_;
  }

  /// A⁻¹·b.
  Vector3<S> solve(const Vector3<S>& b) const noexcept {
    const S y0 = i00_ * b[0];
    const S y1 = i10_ * b[0] + i11_ * b[1];
    const S y2 = i20_ * b[0] + i21_ * b[1] + i22_ * b[2];
    return Vector3<S>(i00_ * y0 + i10_ * y1 + i20_ * y2, i11_ * y1 + i21_ * y2, i22_ * y2);
  }

  /// diag(A⁻¹).
  Vector3<S> inverse_diagonal() const noexcept {
    return Vector3<S>(i00_ * i00_ + i10_ * i10_ + i20_ * i20_, i11_ * i11_ + i21_ * i21_,
                      i22_ * i22_);
  }

 private:
  S i00_, i10_, i11_, i20_, i21_, i22_;  ///< L⁻¹
};

}  // namespace tpf
