// The contact force at a pad from the external joint torques, with the pad's normal-force reading
// as a prior: regularised least squares, with a validity flag and condition numbers.
#pragma once

#include <cmath>
#include <limits>

#include "tpf/common/all_finite.hpp"
#include "tpf/common/cholesky3.hpp"
#include "tpf/common/gram_eigenvalues3.hpp"
#include "tpf/common/small_products.hpp"
#include "tpf/common/symmetric_eigenvalues2.hpp"
#include "tpf/common/types.hpp"

namespace tpf {

/// Settings of estimate_contact_force.
template <typename S>
struct ContactForceSettings {
  /// σ_τ: std of the external-torque estimate [N·m] when no per-joint σ is given.
  S torque_noise_nm = S(0.05);
  S prior_relative = S(0.5);  ///< σ_Fn = prior_relative·F_pad + prior_floor_n: the pad is rough
  S prior_floor_n = S(1);
  /// σ_t = shear_relative·F_pad + prior_floor_n: the zero-mean prior on each shear component, a
  /// soft friction cone (a hand's shear on a pad stays below ≈ μ·F_n, μ ≲ 1).
  S shear_relative = S(0.5);
  /// Shear (x, y of the contact frame) is valid when √(λ_min/λ_max) of its information block
  /// (J_xy J_xyᵀ against the largest eigenvalue of JJᵀ) is at least this.
  S min_inverse_condition = S(0.02);
  /// Ridge on the shear, relative to trace(J_c W J_cᵀ): keeps the solve finite when the shear
  /// prior is switched off; small enough never to compete with a prior.
  S shear_regularisation = S(1e-12);
};

/// A contact force estimate. Contact frame: z = the pad's outward normal (a push has f_z < 0).
template <typename S>
struct ContactForce {
  Vector3<S> force_contact = Vector3<S>::Zero();  ///< [N], contact frame
  Vector3<S> force_world = Vector3<S>::Zero();    ///< [N], world frame
  Vector3<S> point_world = Vector3<S>::Zero();    ///< where it acts [m]
  S condition = S(0);          ///< σ_max/σ_min of the contact Jacobian alone (+inf when rank < 3)
  S inverse_condition = S(0);  ///< σ_min/σ_max of the contact Jacobian alone, in [0, 1]
  S shear_inverse_condition = S(0);  ///< the same for the shear block, normal known from the pad
  /// Posterior std of each component of force_contact [N] (√diag A⁻¹ of the solve below).
  Vector3<S> force_std_contact = Vector3<S>::Zero();
  int pad = -1;                    ///< pad index, −1 when no pad is in contact
  bool observable_by_arm = false;  ///< the Jacobian alone fixes all three components
  bool valid = false;              ///< the estimate is meaningful (see estimate_contact_force)
};

/// The per-joint scratch of estimate_contact_force: locals at a fixed joint count; at
/// Eigen::Dynamic sized once by resize(n) and kept by the caller, so that the call allocates
/// nothing.
template <typename S, int N>
struct ContactForceWorkspace {
  Eigen::Matrix<S, 3, N> Jc;   ///< J_c = Rᵀ·J_v
  Eigen::Matrix<S, 3, N> JcW;  ///< J_c·W
  JointVector<S, N> w;         ///< W's diagonal, 1/σ_τ²

  void resize(int joints) {
    Jc.resize(3, joints);
    JcW.resize(3, joints);
    w.resize(joints);
  }
};

namespace detail {

/// J_c = Rᵀ·J_v: the linear rows of a world Jacobian in the frame whose axes are R's columns,
/// column by column (rotate_back), into Jc (sized like J_world).
template <typename S, int N>
void linear_rows_in_frame(const Jacobian<S, N>& J_world, const Matrix3<S>& R,
                          Eigen::Matrix<S, 3, N>& Jc) noexcept {
  for (int j = 0; j < J_world.cols(); ++j)
    Jc.col(j) = rotate_back(R, Vector3<S>(J_world(0, j), J_world(1, j), J_world(2, j)));
}

/// a·bᵀ for a product known to be symmetric (b = a or b = a·diag(w)): the lower triangle summed
/// over the columns in order, mirrored to the upper; Eigen's product without its temporaries,
/// equal to it to rounding.
template <typename S, int N>
Matrix3<S> symmetric_product(const Eigen::Matrix<S, 3, N>& a,
                             const Eigen::Matrix<S, 3, N>& b) noexcept {
  Matrix3<S> m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c <= r; ++c) {
      S sum = a(r, 0) * b(c, 0);
      for (int j = 1; j < a.cols(); ++j)
        sum += a(r, j) * b(c, j);
      m(r, c) = m(c, r) = sum;
    }
  return m;
}

}  // namespace detail

/// Solves for the force f (contact frame) acting at the pad point from the external torque τ [N·m]
/// (what the environment applies to the robot, τ = J_cᵀ f with J_c = Rᵀ·J_v the linear rows of the
/// point Jacobian in the contact frame), weighting each joint by the std σ_τ,j of its τ estimate
/// and the pad reading F_pad ≥ 0 [N] as a prior f ≈ f₀ = (0, 0, −F_pad) — the maximum a posteriori
/// force under Gaussian errors:
///   (J_c W J_cᵀ + Λ) f = J_c W τ + Λ f₀,  W = diag(1/σ_τ,j²),  Λ = diag(1/σ_t², 1/σ_t², 1/σ_n²),
/// σ_n = prior_relative·F_pad + prior_floor_n, σ_t = shear_relative·F_pad + prior_floor_n, plus a
/// tiny ridge shear_regularisation·trace(J_c W J_cᵀ) on the shear (keeps the solve finite without
/// a prior). Where the arm sees a component well (small σ_τ, good conditioning) the torques decide
/// it; where it does not (proximal pads, rank < 3, joints stuck in friction) the pad does. The
/// posterior std √diag (J_c W J_cᵀ + Λ)⁻¹ comes with the estimate. The Jacobian's own
/// conditioning gives `condition`, `inverse_condition`, `observable_by_arm` and `valid` (the shear
/// block, normal fixed by the pad, has inverse condition ≥ min_inverse_condition); when the shear
/// is unobservable, `valid` is false and the numbers say why. Allocation-free.
///
/// Cost: the 3×3 eigenvalues in closed form where at most two joints move the pad
/// (gram_eigenvalues3), else by cyclic Jacobi rotations (symmetric_eigenvalues3: to ≈ ε·λ_max,
/// where Eigen's closed form loses the smallest eigenvalue to ≈ 1e-13·λ_max, which the rank test
/// cannot afford), the 2×2 shear block's in closed form (Eigen's computeDirect arithmetic), the
/// solve by a written-out Cholesky factor (A is positive definite through the priors); the
/// factorisation changed from Eigen's pivoting LDLT, equal to ≈ 5e-12 relative.
template <typename S, int N>
ContactForce<S> estimate_contact_force(const Jacobian<S, N>& J_world, const Matrix3<S>& R_contact,
                                       const JointVector<S, N>& tau_ext,
                                       const JointVector<S, N>& tau_sigma_nm, S pad_force,
                                       const ContactForceSettings<S>& settings,
                                       ContactForceWorkspace<S, N>& work) noexcept {
  using std::max, std::sqrt;
  ContactForce<S> out;
  const Eigen::Matrix<S, 3, N>& Jc = work.Jc;
  detail::linear_rows_in_frame(J_world, R_contact, work.Jc);
  const Matrix3<S> info = detail::symmetric_product(Jc, Jc);  // J_c J_cᵀ: the geometry alone

  const Vector3<S> lambda = gram_eigenvalues3(Jc, info).cwiseMax(S(0));  // ascending
  const S lambda_max = lambda[2];
  if (!(lambda_max > S(0))) return out;  // the pad's link does not move with any joint
  out.inverse_condition = sqrt(lambda[0] / lambda_max);
  out.condition =
      lambda[0] > S(0) ? sqrt(lambda_max / lambda[0]) : std::numeric_limits<S>::infinity();
  const S shear_lambda_min = smaller_symmetric_eigenvalue2(info);  // of the top-left 2×2 block
  out.shear_inverse_condition = sqrt(max(shear_lambda_min, S(0)) / lambda_max);
  out.observable_by_arm = out.inverse_condition >= settings.min_inverse_condition;

  work.w = tau_sigma_nm.cwiseAbs2().cwiseInverse();
  work.JcW.noalias() = Jc * work.w.asDiagonal();
  const Eigen::Matrix<S, 3, N>& JcW = work.JcW;
  Matrix3<S> A = detail::symmetric_product(JcW, Jc);
  const S sigma_n = settings.prior_relative * pad_force + settings.prior_floor_n;
  const S sigma_t = settings.shear_relative * pad_force + settings.prior_floor_n;
  const S ridge = settings.shear_regularisation * A.trace();
  A(0, 0) += ridge + S(1) / (sigma_t * sigma_t);
  A(1, 1) += ridge + S(1) / (sigma_t * sigma_t);
  A(2, 2) += S(1) / (sigma_n * sigma_n);
  Vector3<S> b;
  b.noalias() = JcW * tau_ext;
  b[2] += -pad_force / (sigma_n * sigma_n);
  const Cholesky3<S> cholesky(A);
  out.force_contact = cholesky.solve(b);
  out.force_std_contact = cholesky.inverse_diagonal().cwiseMax(S(0)).cwiseSqrt();
  out.force_world = R_contact * out.force_contact;
  out.valid = out.shear_inverse_condition >= settings.min_inverse_condition &&
              all_finite(out.force_contact);
  return out;
}

/// The same with its scratch on the stack (allocated at Eigen::Dynamic).
template <typename S, int N>
ContactForce<S> estimate_contact_force(
    const Jacobian<S, N>& J_world, const Matrix3<S>& R_contact, const JointVector<S, N>& tau_ext,
    const JointVector<S, N>& tau_sigma_nm, S pad_force,
    const ContactForceSettings<S>& settings = {}) noexcept(N != Eigen::Dynamic) {
  ContactForceWorkspace<S, N> work;
  if constexpr (N == Eigen::Dynamic) work.resize(static_cast<int>(J_world.cols()));
  return estimate_contact_force(J_world, R_contact, tau_ext, tau_sigma_nm, pad_force, settings,
                                work);
}

/// The same with one σ_τ = settings.torque_noise_nm for every joint.
template <typename S, int N>
ContactForce<S> estimate_contact_force(
    const Jacobian<S, N>& J_world, const Matrix3<S>& R_contact, const JointVector<S, N>& tau_ext,
    S pad_force, const ContactForceSettings<S>& settings = {}) noexcept(N != Eigen::Dynamic) {
  return estimate_contact_force(
      J_world, R_contact, tau_ext,
      JointVector<S, N>::Constant(tau_ext.size(), settings.torque_noise_nm).eval(), pad_force,
      settings);
}

}  // namespace tpf
