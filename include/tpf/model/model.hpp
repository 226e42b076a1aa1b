// The immutable description of a serial arm of N revolute joints (Pinocchio's Model).
#pragma once

#include <array>
#include <cmath>
#include <string>

#include "tpf/common/types.hpp"
#include "tpf/model/inertia.hpp"

namespace tpf {

/// What the per-cycle algorithms need of a Model that does not depend on q: computed once by
/// Model::update_constants() from the placements, axes and inertias (and the copy of those it was
/// computed from, which debug builds check against the model on every kinematics call).
template <typename S, int N>
struct ModelConstants {
  /// Joint k's rotation in its parent: liMi[k].R = placement.R + sin q·rotation_sine[k] +
  /// (1 − cos q)·rotation_versine[k], with rotation_sine = placement.R·[z]×, rotation_versine =
  /// placement.R·[z]×² (Rodrigues' formula, z the unit axis).
  std::array<Matrix3<S>, N> rotation_sine, rotation_versine;
  std::array<Vector3<S>, N + 1> first_moment;          ///< h = m·c per link [kg·m].
  std::array<Matrix3<S>, N + 1> inertia_about_origin;  ///< I_o per link [kg·m²].
  std::array<S, N + 2> subtree_mass{};  ///< Σ_{j ≥ k} m_j: links k..N ([N + 1] = 0) [kg].
  /// ±(i + 1) when joint k's axis is ±e_i (its world axis is then ± a column of the link's
  /// rotation, no product), 0 for any other axis.
  std::array<int, N> axis_coordinate{};

  std::array<Transform<S>, N> placements_used;  ///< the sources of the constants above
  std::array<Vector3<S>, N> axes_used;
  std::array<Inertia<S>, N + 1> inertias_used;
};

/// A serial chain of N revolute joints with its inertias and drive data. Immutable after loading;
/// every per-cycle function takes it by const reference together with a Data workspace.
///
/// Frames: link 0 is the base (world frame). Link k (1..N) moves with joint k. The frame of joint k
/// sits at joint_placements[k-1] in link k−1's frame; link k's frame is that frame rotated by q_k
/// about axes[k-1]. Joint indices in vectors are 0-based (q(0) is joint 1).
template <typename S, int N>
struct Model {
  static_assert(N >= 1, "a model has at least one joint");
  using Scalar = S;
  static constexpr int joints = N;

  std::string name;
  std::array<std::string, N> joint_names;
  std::array<std::string, N + 1> link_names;  ///< [0] is the base link.

  std::array<Transform<S>, N> joint_placements;  ///< joint k frame in link k−1 frame, at q = 0.
  std::array<Vector3<S>, N> axes;                ///< unit rotation axis in the joint frame.
  std::array<Inertia<S>, N + 1> inertias;  ///< per link, in its own frame ([0]: base, unused).

  JointVector<S, N> armature = JointVector<S, N>::Zero();  ///< reflected rotor inertia [kg·m²].
  JointVector<S, N> gear_ratio = JointVector<S, N>::Ones();
  JointVector<S, N> torque_constant = JointVector<S, N>::Ones();  ///< [N·m/A], output side.
  JointVector<S, N> current_limit = JointVector<S, N>::Zero();    ///< [mA].
  /// Position limits [rad]; ±∞ for a continuous joint (see has_position_limits).
  JointVector<S, N> lower = JointVector<S, N>::Zero();
  JointVector<S, N> upper = JointVector<S, N>::Zero();
  JointVector<S, N> velocity_limit = JointVector<S, N>::Zero();  ///< [rad/s].
  JointVector<S, N> effort_limit = JointVector<S, N>::Zero();    ///< [N·m].

  Vector3<S> gravity = Vector3<S>(S(0), S(0), S(-9.81));  ///< in the world frame [m/s²].

  /// Derived from joint_placements, axes and inertias; update_constants() after changing those.
  ModelConstants<S, N> constants;

  /// Recomputes `constants` from joint_placements, axes and inertias. make_model and cast call
  /// it; a caller that edits a loaded model (e.g. adds a payload to an inertia) calls it again.
  void update_constants() {
    ModelConstants<S, N>& c = constants;
    for (int k = 0; k < N; ++k) {
      const Matrix3<S> K = skew(axes[k]);
      c.rotation_sine[k] = joint_placements[k].R * K;
      c.rotation_versine[k] = c.rotation_sine[k] * K;
      c.axis_coordinate[k] = 0;
      for (int i = 0; i < 3; ++i)
        if (axes[k] == Vector3<S>::Unit(i) || axes[k] == -Vector3<S>::Unit(i))
          c.axis_coordinate[k] = axes[k][i] > S(0) ? i + 1 : -(i + 1);
    }
    c.subtree_mass[N + 1] = S(0);
    for (int k = N; k >= 0; --k) {
      c.first_moment[k] = inertias[k].first_moment();
      c.inertia_about_origin[k] = inertias[k].about_origin();
      c.subtree_mass[k] = c.subtree_mass[k + 1] + inertias[k].mass;
    }
    c.placements_used = joint_placements;
    c.axes_used = axes;
    c.inertias_used = inertias;
  }

  /// Whether `constants` were computed from the current placements, axes and inertias.
  bool constants_current() const {
    const ModelConstants<S, N>& c = constants;
    for (int k = 0; k < N; ++k)
      if (c.placements_used[k].R != joint_placements[k].R ||
          c.placements_used[k].p != joint_placements[k].p || c.axes_used[k] != axes[k])
        return false;
    for (int k = 0; k <= N; ++k)
      if (c.inertias_used[k].mass != inertias[k].mass ||
          c.inertias_used[k].com != inertias[k].com ||
          c.inertias_used[k].rotational != inertias[k].rotational)
        return false;
    return true;
  }

  /// Index (1..N) of the link called `link_name`, or −1.
  int link_index(const std::string& link_name) const {
    for (int k = 0; k <= N; ++k)
      if (link_names[k] == link_name) return k;
    return -1;
  }

  /// Whether joint j (0-based) moves within finite limits lower < upper; a continuous joint has
  /// ±∞ and no range to draw positions from.
  bool has_position_limits(int j) const {
    using std::isfinite;
    return isfinite(lower[j]) && isfinite(upper[j]) && lower[j] < upper[j];
  }

  /// The same model in another scalar type (e.g. float for a controller).
  template <typename T>
  Model<T, N> cast() const {
    Model<T, N> m;
    m.name = name;
    m.joint_names = joint_names;
    m.link_names = link_names;
    for (int k = 0; k < N; ++k) {
      m.joint_placements[k] = joint_placements[k].template cast<T>();
      m.axes[k] = axes[k].template cast<T>();
    }
    for (int k = 0; k <= N; ++k)
      m.inertias[k] = inertias[k].template cast<T>();
    m.armature = armature.template cast<T>();
    m.gear_ratio = gear_ratio.template cast<T>();
    m.torque_constant = torque_constant.template cast<T>();
    m.current_limit = current_limit.template cast<T>();
    m.lower = lower.template cast<T>();
    m.upper = upper.template cast<T>();
    m.velocity_limit = velocity_limit.template cast<T>();
    m.effort_limit = effort_limit.template cast<T>();
    m.gravity = gravity.template cast<T>();
    m.update_constants();
    return m;
  }
};

}  // namespace tpf
