// Fixed-size Eigen aliases used throughout the core. N is the joint count, fixed at compile time.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <type_traits>
#include <vector>

namespace tpf {

/// A parameter type that takes no part in template deduction: S and N come from the Model, and
/// Eigen expressions (q + h * dq, Vec::Zero()) convert to the fixed-size type on the stack.
template <typename T>
using NoDeduce = std::type_identity_t<T>;

template <typename S, int N>
using JointVector = Eigen::Matrix<S, N, 1>;

/// Per-channel storage of a count fixed at compile time (std::array) or, with Eigen::Dynamic,
/// chosen at start-up (std::vector: the offline tools, which read the pad count from a file).
template <typename T, int Count>
using ChannelArray = std::conditional_t<Count == Eigen::Dynamic, std::vector<T>,
                                        std::array<T, std::size_t(Count < 0 ? 0 : Count)>>;
template <typename S, int N>
using JointMatrix = Eigen::Matrix<S, N, N>;
template <typename S>
using Vector3 = Eigen::Matrix<S, 3, 1>;
template <typename S>
using Matrix3 = Eigen::Matrix<S, 3, 3>;
template <typename S>
using Vector6 = Eigen::Matrix<S, 6, 1>;
/// 6×N Jacobian, rows ordered [linear; angular].
template <typename S, int N>
using Jacobian = Eigen::Matrix<S, 6, N>;

/// A rigid transform, rotation R and translation p: x_parent = R·x_child + p.
template <typename S>
struct Transform {
  Matrix3<S> R = Matrix3<S>::Identity();
  Vector3<S> p = Vector3<S>::Zero();

  Vector3<S> apply(const Vector3<S>& x) const { return R * x + p; }
  Transform operator*(const Transform& b) const { return {R * b.R, R * b.p + p}; }
  template <typename T>
  Transform<T> cast() const {
    return {R.template cast<T>(), p.template cast<T>()};
  }
};

/// The cross-product matrix [v]×, with [v]× w = v × w.
template <typename S>
Matrix3<S> skew(const Vector3<S>& v) {
  Matrix3<S> m;
  m << S(0), -v.z(), v.y(), v.z(), S(0), -v.x(), -v.y(), v.x(), S(0);
  return m;
}

}  // namespace tpf
