// The immutable description of a serial arm of N revolute or prismatic joints (Pinocchio's Model):
// N fixed at compile time in a controller, or Eigen::Dynamic (sized by resize or make_model) in the
// tools.
#pragma once

#include <array>
#include <cassert>
#include <cmath>
#include <string>

#include "tpf/common/types.hpp"
#include "tpf/model/inertia.hpp"

namespace tpf {

/// How a joint moves its child link: a rotation about its axis (q in rad, q̇ in rad/s, effort in
/// N·m) or a translation along it (q in m, q̇ in m/s, effort in N).
enum class JointType : unsigned char { revolute, prismatic };

/// What the per-cycle algorithms need of a Model that does not depend on q: computed once by
/// Model::update_constants() from the placements, axes and inertias (and the copy of those it was
/// computed from, which debug builds check against the model on every kinematics call).
template <typename S, int N>
struct ModelConstants {
  /// Joint k's rotation in its parent: liMi[k].R = placement.R + sin q·rotation_sine[k] +
  /// (1 − cos q)·rotation_versine[k], with rotation_sine = placement.R·[z]×, rotation_versine =
  /// placement.R·[z]×² (Rodrigues' formula, z the unit axis).
  LinkArray<Matrix3<S>, N> rotation_sine, rotation_versine;
  LinkArray<Vector3<S>, N, 1> first_moment;          ///< h = m·c per link [kg·m].
  LinkArray<Matrix3<S>, N, 1> inertia_about_origin;  ///< I_o per link [kg·m²].
  LinkArray<S, N, 2> subtree_mass{};  ///< Σ_{j ≥ k} m_j: links k..N ([N + 1] = 0) [kg].
  /// ±(i + 1) when joint k's axis is ±e_i (its world axis is then ± a column of the link's
  /// rotation, no product), 0 for any other axis.
  LinkArray<int, N> axis_coordinate{};
  /// placement.R·axis: a prismatic joint k's direction of travel in link k−1's frame, so that
  /// liMi[k].p = placement.p + q·translation_axis[k] (zero for a revolute joint).
  LinkArray<Vector3<S>, N> translation_axis;
  /// Whether any joint is prismatic. The per-cycle algorithms branch on it once per call: an arm
  /// of revolute joints runs code without any per-joint test of the type.
  bool has_prismatic = false;

  LinkArray<Transform<S>, N> placements_used;  ///< the sources of the constants above
  LinkArray<Vector3<S>, N> axes_used;
  LinkArray<Inertia<S>, N, 1> inertias_used;
  LinkArray<JointType, N> types_used{};

  /// Sizes the per-link arrays for n joints (Eigen::Dynamic; a fixed N is already sized).
  void resize(int n) {
    const auto joints = static_cast<std::size_t>(n);
    resize_storage(rotation_sine, joints);
    resize_storage(rotation_versine, joints);
    resize_storage(first_moment, joints + 1);
    resize_storage(inertia_about_origin, joints + 1);
    resize_storage(subtree_mass, joints + 2);
    resize_storage(axis_coordinate, joints);
    resize_storage(translation_axis, joints);
  }
};

/// A serial chain of N revolute or prismatic joints with its inertias and drive data. Immutable
/// after loading; every per-cycle function takes it by const reference together with a Data
/// workspace.
///
/// Frames: link 0 is the base (world frame). Link k (1..N) moves with joint k. The frame of joint k
/// sits at joint_placements[k-1] in link k−1's frame; link k's frame is that frame rotated by q_k
/// about axes[k-1] (a revolute joint) or moved by q_k along it (a prismatic joint). Per-joint
/// quantities are in the joint's own units: rad, rad/s, N·m and kg·m² for a revolute joint; m,
/// m/s, N and kg (armature: a reflected mass) for a prismatic one. Joint indices in vectors are
/// 0-based (q(0) is joint 1).
///
/// With N = Eigen::Dynamic the same model is sized at run time (resize(n), or make_model from a
/// robot file): one compiled copy of every algorithm serves any joint count.
template <typename S, int N>
struct Model {
  static_assert(N >= 1 || N == Eigen::Dynamic, "a model has at least one joint");
  using Scalar = S;
  static constexpr int joints =
      N;  ///< the compile-time count, Eigen::Dynamic if chosen at run time

  std::string name;
  LinkArray<std::string, N> joint_names;
  LinkArray<std::string, N, 1> link_names;  ///< [0] is the base link.

  LinkArray<Transform<S>, N> joint_placements;  ///< joint k frame in link k−1 frame, at q = 0.
  LinkArray<Vector3<S>, N> axes;          ///< unit rotation or translation axis in the joint frame.
  LinkArray<JointType, N> joint_types{};  ///< revolute unless set (then update_constants).
  LinkArray<Inertia<S>, N, 1> inertias;   ///< per link, in its own frame ([0]: base, unused).

  using Vector = JointVector<S, N>;
  Vector armature = zero_or_empty<Vector>();  ///< reflected rotor inertia [kg·m²] or mass [kg].
  Vector gear_ratio = ones_or_empty();
  Vector torque_constant = ones_or_empty();        ///< [N·m/A] or [N/A], output side.
  Vector current_limit = zero_or_empty<Vector>();  ///< [mA].
  /// Position limits [rad] or [m]; ±∞ for a continuous joint (see has_position_limits).
  Vector lower = zero_or_empty<Vector>();
  Vector upper = zero_or_empty<Vector>();
  Vector velocity_limit = zero_or_empty<Vector>();  ///< [rad/s] or [m/s].
  Vector effort_limit = zero_or_empty<Vector>();    ///< [N·m] or [N].

  Vector3<S> gravity = Vector3<S>(S(0), S(0), S(-9.81));  ///< in the world frame [m/s²].

  /// The transmission's coupling C (motors × joints, motor m in joint m's row): motor m rotates
  /// with θ_m = gear_ratio(m)·Σ_j C(m, j)·q_j, and its torque at the output scale τ_m acts on the
  /// joints as τ_j = Σ_m C(m, j)·τ_m. The armature and the drives' friction act through it,
  /// Cᵀ·diag(armature)·C·q̈ and Cᵀ·f(C·q̇). The identity (each motor drives its own joint)
  /// unless the robot file couples motors (a differential wrist: θ_6 ∝ q_5 + q_6).
  JointMatrix<S, N> coupling = identity_or_empty();
  bool coupled = false;  ///< C is not the identity (set_coupling)

  /// Sets C; `coupled` says whether it differs from the identity.
  void set_coupling(const JointMatrix<S, N>& c) {
    coupling = c;
    const int n = joint_count();
    coupled = !(c.rows() == n && c.cols() == n && c.isIdentity(S(0)));
  }

  /// Motor m's velocity at the output scale, (C·v)_m (v: q̇ or q̈). Allocation-free.
  S motor_rate(int m, const Vector& v) const {
    return coupled ? coupling.row(m).dot(v) : v(m);
  }
  /// Adds motor m's output-scale torque t to the joint torques tau: tau += t·C(m, :)ᵀ.
  void add_motor_torque(int m, const S& t, Vector& tau) const {
    if (!coupled) {
      tau(m) += t;
      return;
    }
    for (int j = 0; j < joint_count(); ++j)
      tau(j) += coupling(m, j) * t;
  }

  /// Derived from joint_placements, axes and inertias; update_constants() after changing those.
  ModelConstants<S, N> constants;

  /// The number of joints: N, or the run-time count of an Eigen::Dynamic model.
  constexpr int joint_count() const noexcept {
    if constexpr (N == Eigen::Dynamic)
      return static_cast<int>(axes.size());
    else
      return N;
  }

  /// Sizes every per-joint and per-link member for n joints with the defaults of a fixed-size
  /// model (identity placements, z axes, massless links, no armature, unit ratio and K_t, zero
  /// limits). For Eigen::Dynamic; a fixed N is already sized (n must equal it).
  void resize(int n) {
    assert(n >= 1 && (N == Eigen::Dynamic || n == N));
    const auto joints_n = static_cast<std::size_t>(n);
    resize_storage(joint_names, joints_n);
    resize_storage(link_names, joints_n + 1);
    resize_storage(joint_placements, joints_n);
    resize_storage(axes, joints_n);
    resize_storage(joint_types, joints_n);
    for (JointType& type : joint_types)
      type = JointType::revolute;
    resize_storage(inertias, joints_n + 1);
    for (Vector* v : {&armature, &current_limit, &lower, &upper, &velocity_limit, &effort_limit})
      *v = Vector::Zero(n);
    gear_ratio = Vector::Ones(n);
    torque_constant = Vector::Ones(n);
    coupling = JointMatrix<S, N>::Identity(n, n);
    coupled = false;
    constants.resize(n);
  }

  /// Recomputes `constants` from joint_placements, axes and inertias. make_model and cast call
  /// it; a caller that edits a loaded model (e.g. adds a payload to an inertia) calls it again.
  void update_constants() {
    ModelConstants<S, N>& c = constants;
    const int n = joint_count();
    c.resize(n);
    c.has_prismatic = false;
    for (int k = 0; k < n; ++k) {
      const Matrix3<S> K = skew(axes[k]);
      c.rotation_sine[k] = joint_placements[k].R * K;
      c.rotation_versine[k] = c.rotation_sine[k] * K;
      c.axis_coordinate[k] = 0;
      for (int i = 0; i < 3; ++i)
        if (axes[k] == Vector3<S>::Unit(i) || axes[k] == -Vector3<S>::Unit(i))
          c.axis_coordinate[k] = axes[k][i] > S(0) ? i + 1 : -(i + 1);
      c.translation_axis[k] = Vector3<S>::Zero();
      if (joint_types[k] == JointType::prismatic) {
        c.translation_axis[k] = joint_placements[k].R * axes[k];
        c.has_prismatic = true;
      }
    }
    c.subtree_mass[n + 1] = S(0);
    for (int k = n; k >= 0; --k) {
      c.first_moment[k] = inertias[k].first_moment();
      c.inertia_about_origin[k] = inertias[k].about_origin();
      c.subtree_mass[k] = c.subtree_mass[k + 1] + inertias[k].mass;
    }
    c.placements_used = joint_placements;
    c.axes_used = axes;
    c.inertias_used = inertias;
    c.types_used = joint_types;
  }

  /// Whether `constants` were computed from the current placements, axes and inertias.
  bool constants_current() const {
    const ModelConstants<S, N>& c = constants;
    const int n = joint_count();
    if (static_cast<int>(c.placements_used.size()) != n ||
        static_cast<int>(c.inertias_used.size()) != n + 1)
      return false;
    for (int k = 0; k < n; ++k)
      if (c.placements_used[k].R != joint_placements[k].R ||
          c.placements_used[k].p != joint_placements[k].p || c.axes_used[k] != axes[k] ||
          c.types_used[k] != joint_types[k])
        return false;
    for (int k = 0; k <= n; ++k)
      if (c.inertias_used[k].mass != inertias[k].mass ||
          c.inertias_used[k].com != inertias[k].com ||
          c.inertias_used[k].rotational != inertias[k].rotational)
        return false;
    return true;
  }

  /// Whether joint j (0-based) is prismatic.
  bool is_prismatic(int j) const { return joint_types[j] == JointType::prismatic; }

  /// Index (1..N) of the link called `link_name`, or −1.
  int link_index(const std::string& link_name) const {
    for (int k = 0; k <= joint_count(); ++k)
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
    const int n = joint_count();
    m.resize(n);
    m.name = name;
    m.joint_names = joint_names;
    m.link_names = link_names;
    m.joint_types = joint_types;
    for (int k = 0; k < n; ++k) {
      m.joint_placements[k] = joint_placements[k].template cast<T>();
      m.axes[k] = axes[k].template cast<T>();
    }
    for (int k = 0; k <= n; ++k)
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
    m.set_coupling(coupling.template cast<T>());
    m.update_constants();
    return m;
  }

 private:
  static JointMatrix<S, N> identity_or_empty() {
    if constexpr (N == Eigen::Dynamic)
      return JointMatrix<S, N>();
    else
      return JointMatrix<S, N>::Identity();
  }
  static Vector ones_or_empty() {
    if constexpr (N == Eigen::Dynamic)
      return Vector();
    else
      return Vector::Ones();
  }
};

namespace detail {

/// Runs f() as a call that is never inlined: the prismatic variant of a per-cycle algorithm, so
/// that it does not grow the revolute variant's caller. Together with [[gnu::flatten]] on both
/// variants' recursions this keeps the revolute code as fast as it was alone (without them, GCC
/// inlined less of it: RNEA 118 → 210 ns, CRBA 114 → 161 ns on the 4-DoF arm).
template <typename F>
[[gnu::noinline]] void out_of_line(const F& f) {
  f();
}

}  // namespace detail
}  // namespace tpf
