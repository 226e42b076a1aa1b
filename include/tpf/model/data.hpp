// The workspace of the per-cycle algorithms (Pinocchio's Data): allocated once, reused every cycle.
#pragma once

#include <Eigen/Cholesky>
#include <array>

#include "tpf/common/types.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// Results and scratch space of kinematics and dynamics for one Model. Fixed size: constructing it
/// is the only allocation-free "allocation" there is; nothing in it grows. At Eigen::Dynamic the
/// constructor sizes it for the model's joint count (once, at start-up).
template <typename S, int N>
struct Data {
  Data() = default;
  explicit Data(const Model<S, N>& model) {
    if constexpr (N == Eigen::Dynamic) resize(model.joint_count());
  }

  // Kinematics (forward_kinematics).
  LinkArray<Transform<S>, N, 1> liMi;      ///< link k in link k−1 at the current q ([0] unused).
  LinkArray<Transform<S>, N, 1> oMi;       ///< link k in the world frame ([0] = identity).
  LinkArray<Vector3<S>, N, 1> axis_world;  ///< joint k axis in the world frame ([0] unused).

  // Recursive Newton–Euler, in link frames.
  LinkArray<Vector3<S>, N, 1> omega, domega, acc;  ///< ω, ω̇, linear acceleration of the origin.
  LinkArray<Vector3<S>, N, 1> force,
      moment;  ///< wrench link k−1 applies to link k, at k's origin.

  JointVector<S, N> tau = zero_or_empty<JointVector<S, N>>();  ///< rnea output [N·m].
  JointVector<S, N> g = zero_or_empty<JointVector<S, N>>();    ///< gravity torque G(q).
  JointVector<S, N> ddq = zero_or_empty<JointVector<S, N>>();  ///< forward_dynamics output.
  JointMatrix<S, N> M = zero_or_empty<JointMatrix<S, N>>();  ///< joint-space inertia (armature in).
  JointMatrix<S, N> C = zero_or_empty<JointMatrix<S, N>>();  ///< Coriolis matrix, C + Cᵀ = Ṁ.

  // Composite rigid bodies of links k..N (mass matrix, gravity), in link frames; their masses are
  // model constants (Model::constants.subtree_mass).
  LinkArray<Vector3<S>, N, 1> composite_first_moment;
  LinkArray<Matrix3<S>, N, 1> composite_inertia;

  Eigen::LLT<JointMatrix<S, N>> mass_factor;  ///< Cholesky factor of M (forward_dynamics).

 private:
  void resize(int n) {
    const auto links = static_cast<std::size_t>(n + 1);
    for (auto* a : {&liMi, &oMi})
      resize_storage(*a, links);
    for (auto* a : {&axis_world, &omega, &domega, &acc, &force, &moment, &composite_first_moment})
      resize_storage(*a, links);
    resize_storage(composite_inertia, links);
    tau = g = ddq = JointVector<S, N>::Zero(n);
    M = C = JointMatrix<S, N>::Zero(n, n);
    mass_factor = Eigen::LLT<JointMatrix<S, N>>(n);
  }
};

}  // namespace tpf
