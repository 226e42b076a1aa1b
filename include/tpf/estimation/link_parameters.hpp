// The rigid body (and the regressor's friction columns) as linear link parameters, evaluated by
// Newton–Euler on kinematics already computed: the fast per-cycle form of τ = Y(q, q̇, q̈)·π.
#pragma once

#include <array>

#include "tpf/common/types.hpp"
#include "tpf/dynamics/regressor.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// The standard parameters of the regressor (dynamic_parameters order) held per link in the form
/// the dynamics is linear in: mass m_k [kg], first moment h_k = m_k·c_k [kg·m] and rotational
/// inertia about the link origin I_o,k [kg·m²] (link frame), plus per joint the armature
/// I_a [kg·m²], Coulomb f_c [N·m] and viscous f_v [N·m·s/rad] columns. Nothing here needs to be
/// physical (m may be 0 or negative, c is never formed), so any parameter vector π — e.g. the
/// identified base values scattered onto their columns — has an exact link form.
template <typename S, int N>
struct LinkParameters {
  LinkArray<S, N> mass{};
  LinkArray<Vector3<S>, N> first_moment{};
  LinkArray<Matrix3<S>, N> inertia{};
  JointVector<S, N> armature = zero_or_empty<JointVector<S, N>>();
  JointVector<S, N> coulomb = zero_or_empty<JointVector<S, N>>();
  JointVector<S, N> viscous = zero_or_empty<JointVector<S, N>>();
};

/// The link form of a standard parameter vector π (13n entries, dynamic_parameters order:
/// [m, h_x, h_y, h_z, I_xx, I_xy, I_xz, I_yy, I_yz, I_zz] per link, then I_a, f_c, f_v per joint).
/// Allocation-free at a fixed joint count.
template <typename S, int N>
LinkParameters<S, N> link_parameters(const DynamicParameters<S, N>& pi) noexcept(N !=
                                                                                 Eigen::Dynamic) {
  const int n = static_cast<int>(pi.size()) / 13;
  LinkParameters<S, N> p;
  resize_storage(p.mass, n);
  resize_storage(p.first_moment, n);
  resize_storage(p.inertia, n);
  for (int k = 0; k < n; ++k) {
    const auto v = pi.template segment<10>(10 * k);
    p.mass[k] = v(0);
    p.first_moment[k] = v.template segment<3>(1);
    p.inertia[k] << v(4), v(5), v(6), v(5), v(7), v(8), v(6), v(8), v(9);
  }
  p.armature = pi.segment(10 * n, n);
  p.coulomb = pi.segment(11 * n, n);
  p.viscous = pi.segment(12 * n, n);
  return p;
}

/// τ = Y(q, q̇, q̈)·π [N·m] by the two Newton–Euler passes on the link transforms already in
/// data.liMi (forward_kinematics at q first):
///   forward  ω_k = R_kᵀω_{k−1} + z_k q̇_k,  ω̇_k = R_kᵀω̇_{k−1} + z_k q̈_k + (R_kᵀω_{k−1}) × z_k q̇_k,
///            a_k = R_kᵀ(a_{k−1} + ω̇_{k−1} × p_k + ω_{k−1} × (ω_{k−1} × p_k)),  a_0 = −g,
///            f_k = m_k a_k + ω̇_k × h_k + ω_k × (ω_k × h_k),  n_k = I_k ω̇_k + ω_k × I_k ω_k + h_k ×
///            a_k;
///   backward f_k += R_{k+1} f_{k+1},  n_k += R_{k+1} n_{k+1} + p_{k+1} × R_{k+1} f_{k+1},
///            τ_k = z_k·n_k + I_a,k q̈_k + f_c,k sgn(q̇_k) + f_v,k q̇_k;
/// a prismatic joint keeps ω, ω̇, adds z_k q̈_k + 2ω_k × z_k q̇_k to a_k and takes τ_k = z_k·f_k.
/// Equal to the regressor form for every π because both are the same linear map. Into `tau`
/// (sized for the model's joints). Uses data's Newton–Euler scratch; allocation-free.
template <typename S, int N>
void link_parameter_torque(const Model<S, N>& model, const LinkParameters<S, N>& p,
                           Data<S, N>& data, const NoDeduce<JointVector<S, N>>& dq,
                           const NoDeduce<JointVector<S, N>>& ddq,
                           JointVector<S, N>& tau) noexcept {
  const int n = model.joint_count();
  const bool prismatic = model.constants.has_prismatic;
  Vector3<S> w = Vector3<S>::Zero(), dw = Vector3<S>::Zero(), a = -model.gravity;
  for (int k = 1; k <= n; ++k) {
    const Matrix3<S>& R = data.liMi[k].R;
    const Vector3<S>& r = data.liMi[k].p;
    const Vector3<S>& z = model.axes[k - 1];
    a = R.transpose() * (a + dw.cross(r) + w.cross(w.cross(r)));
    const Vector3<S> w_parent = R.transpose() * w;
    if (prismatic && model.joint_types[k - 1] == JointType::prismatic) {
      dw = R.transpose() * dw;
      w = w_parent;
      a += z * ddq(k - 1) + S(2) * w.cross(z * dq(k - 1));
    } else {
      dw = R.transpose() * dw + z * ddq(k - 1) + w_parent.cross(z * dq(k - 1));
      w = w_parent + z * dq(k - 1);
    }
    const Vector3<S>& h = p.first_moment[k - 1];
    const Matrix3<S>& I = p.inertia[k - 1];
    data.force[k] = p.mass[k - 1] * a + dw.cross(h) + w.cross(w.cross(h));
    data.moment[k] = I * dw + w.cross(I * w) + h.cross(a);
  }
  detail::newton_euler_backward_pass(model, data, tau);
  // Per motor, on its own rates through the coupling (per joint without one).
  for (int m = 0; m < n; ++m) {
    const S v = model.motor_rate(m, dq);
    const S sign = v > S(0) ? S(1) : (v < S(0) ? S(-1) : S(0));
    model.add_motor_torque(
        m, p.armature(m) * model.motor_rate(m, ddq) + p.coulomb(m) * sign + p.viscous(m) * v, tau);
  }
}

/// The same returning τ (allocated at Eigen::Dynamic).
template <typename S, int N>
JointVector<S, N> link_parameter_torque(
    const Model<S, N>& model, const LinkParameters<S, N>& p, Data<S, N>& data,
    const NoDeduce<JointVector<S, N>>& dq,
    const NoDeduce<JointVector<S, N>>& ddq) noexcept(N != Eigen::Dynamic) {
  JointVector<S, N> tau;
  tau.resize(model.joint_count());
  link_parameter_torque(model, p, data, dq, ddq, tau);
  return tau;
}

/// Gravity part only, G(q) = Y(q, 0, 0)·π [N·m], on data.liMi: a_k = R_kᵀa_{k−1} (a_0 = −g),
/// f_k = m_k a_k, n_k = h_k × a_k, then the backward pass. Cheaper than link_parameter_torque
/// with zero rates (no ω terms). Allocation-free.
template <typename S, int N>
JointVector<S, N> link_parameter_gravity(const Model<S, N>& model, const LinkParameters<S, N>& p,
                                         Data<S, N>& data) noexcept(N != Eigen::Dynamic) {
  const int n = model.joint_count();
  Vector3<S> a = -model.gravity;
  for (int k = 1; k <= n; ++k) {
    a = data.liMi[k].R.transpose() * a;
    data.force[k] = p.mass[k - 1] * a;
    data.moment[k] = p.first_moment[k - 1].cross(a);
  }
  JointVector<S, N> g;
  g.resize(n);
  detail::newton_euler_backward_pass(model, data, g);
  return g;
}

}  // namespace tpf
