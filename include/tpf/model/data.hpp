// The workspace of the per-cycle algorithms (Pinocchio's Data): allocated once, reused every cycle.
#pragma once

#include <Eigen/Cholesky>
#include <array>

#include "tpf/common/types.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// Results and scratch space of kinematics and dynamics for one Model. Fixed size: constructing it
/// is the only allocation-free "allocation" there is; nothing in it grows.
template <typename S, int N>
struct Data {
  Data() = default;
  explicit Data(const Model<S, N>&) {}

  // Kinematics (forward_kinematics).
  std::array<Transform<S>, N + 1> liMi;  ///< link k in link k−1 at the current q ([0] unused).
  std::array<Transform<S>, N + 1> oMi;   ///< link k in the world frame ([0] = identity).
  std::array<Vector3<S>, N + 1> axis_world;  ///< joint k axis in the world frame ([0] unused).

  // Recursive Newton–Euler, in link frames.
  std::array<Vector3<S>, N + 1> omega, domega, acc;  ///< ω, ω̇, linear acceleration of the origin.
  std::array<Vector3<S>, N + 1> force,
      moment;  ///< wrench link k−1 applies to link k, at k's origin.

  JointVector<S, N> tau = JointVector<S, N>::Zero();  ///< rnea output [N·m].
  JointVector<S, N> g = JointVector<S, N>::Zero();    ///< gravity torque G(q).
  JointVector<S, N> ddq = JointVector<S, N>::Zero();  ///< forward_dynamics output.
  JointMatrix<S, N> M = JointMatrix<S, N>::Zero();    ///< joint-space inertia (with armature).
  JointMatrix<S, N> C = JointMatrix<S, N>::Zero();    ///< Coriolis matrix, C + Cᵀ = Ṁ.

  // Composite rigid bodies of links k..N (mass matrix, gravity), in link frames; their masses are
  // model constants (Model::constants.subtree_mass).
  std::array<Vector3<S>, N + 1> composite_first_moment;
  std::array<Matrix3<S>, N + 1> composite_inertia;

  Eigen::LLT<JointMatrix<S, N>> mass_factor;  ///< Cholesky factor of M (forward_dynamics).
};

}  // namespace tpf
