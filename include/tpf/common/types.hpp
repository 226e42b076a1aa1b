// Eigen aliases used throughout the core. N is the joint count: fixed at compile time in a
// controller (fixed-size storage, nothing allocated per cycle) or Eigen::Dynamic in the offline
// tools (one compiled copy for any count, sized when the model is loaded; Pinocchio's way).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cassert>
#include <string>
#include <type_traits>
#include <vector>

#include "tpf/common/error.hpp"

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

/// Per-joint or per-link storage of N + Extra elements: std::array for a fixed N, std::vector
/// for Eigen::Dynamic (sized by size_for_joints when the model's joint count is known).
template <typename T, int N, int Extra = 0>
using LinkArray = std::conditional_t<N == Eigen::Dynamic, std::vector<T>,
                                     std::array<T, std::size_t(N < 0 ? 0 : N + Extra)>>;

/// Whether N is a compile-time joint count (a controller's) rather than Eigen::Dynamic.
template <int N>
inline constexpr bool is_fixed_joint_count = N != Eigen::Dynamic;

/// The zero of an Eigen type of fixed size, or an empty one of dynamic size (sized later): the
/// default member value that works for both.
template <typename M>
M zero_or_empty() {
  if constexpr (M::SizeAtCompileTime == Eigen::Dynamic)
    return M();
  else
    return M::Zero();
}

/// Sizes per-joint or per-link storage to `count` elements: a std::vector (Eigen::Dynamic) is
/// resized, a std::array already has its size (count must equal it).
template <typename T, std::size_t K>
void resize_storage(std::array<T, K>&, std::size_t count) noexcept {
  assert(count == K);
  (void)count;
}
template <typename T>
void resize_storage(std::vector<T>& storage, std::size_t count) {
  storage.resize(count);
}

/// Throws when a run-time joint count does not fit the compile-time one `To` (Eigen::Dynamic fits
/// any): the shared check of the joint_count_cast functions. Start-up code.
template <int To>
void require_joint_count(int count, const char* what) {
  if constexpr (To != Eigen::Dynamic) {
    if (count != To)
      throw Error(std::string(what) + " has " + std::to_string(count) +
                  " joints, the program asks for " + std::to_string(To));
  }
}

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
