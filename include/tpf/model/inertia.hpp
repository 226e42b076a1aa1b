// Rigid-body inertia of one link, in the link frame.
#pragma once

#include "tpf/common/types.hpp"

namespace tpf {

/// Mass m [kg], centre of mass c [m] and rotational inertia I_c [kg·m²] about c, all in the link
/// frame.
template <typename S>
struct Inertia {
  S mass = S(0);
  Vector3<S> com = Vector3<S>::Zero();
  Matrix3<S> rotational = Matrix3<S>::Zero();

  /// First moment of mass h = m·c.
  Vector3<S> first_moment() const { return mass * com; }

  /// Rotational inertia about the link origin: I_o = I_c + m(cᵀc·1 − c·cᵀ) (parallel-axis theorem).
  Matrix3<S> about_origin() const {
    return rotational + mass * (com.squaredNorm() * Matrix3<S>::Identity() - com * com.transpose());
  }

  /// The 10 standard inertial parameters [m, mc_x, mc_y, mc_z, I_xx, I_xy, I_xz, I_yy, I_yz, I_zz]
  /// with I taken about the link origin: the parameters the dynamics is linear in.
  Eigen::Matrix<S, 10, 1> parameters() const {
    const Vector3<S> h = first_moment();
    const Matrix3<S> I = about_origin();
    Eigen::Matrix<S, 10, 1> pi;
    pi << mass, h.x(), h.y(), h.z(), I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2);
    return pi;
  }

  /// Inverse of parameters(). Requires mass > 0.
  static Inertia from_parameters(const Eigen::Matrix<S, 10, 1>& pi) {
    Inertia in;
    in.mass = pi(0);
    in.com = pi.template segment<3>(1) / pi(0);
    Matrix3<S> I;
    I << pi(4), pi(5), pi(6), pi(5), pi(7), pi(8), pi(6), pi(8), pi(9);
    in.rotational =
        I - in.mass * (in.com.squaredNorm() * Matrix3<S>::Identity() - in.com * in.com.transpose());
    return in;
  }

  template <typename T>
  Inertia<T> cast() const {
    return {T(mass), com.template cast<T>(), rotational.template cast<T>()};
  }
};

}  // namespace tpf
