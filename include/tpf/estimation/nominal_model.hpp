// The nominal model of an arm as identified from a log: what `tpf identify` writes, `tpf diagnose`
// extends and the run-time estimator loads.
//
// Units: SI throughout. The rigid-body base parameters are kg, kg·m, kg·m² (armature kg·m²), and
// every torque (friction, added effects, the predicted effort) is in N·m, whatever the log it was
// identified on held (a log's motor current is converted where it is read, effort_unit.hpp).
// Sign convention: predicted effort is what the drive must produce, τ_meas = rigid + friction +
// τ_res, with τ_res = −τ_ext + what the model lacks (external torque acts on the robot).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

#include "tpf/common/types.hpp"
#include "tpf/dynamics/base_parameters.hpp"
#include "tpf/dynamics/regressor.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/effects/added_effects.hpp"
#include "tpf/estimation/link_parameters.hpp"
#include "tpf/friction/stribeck.hpp"
#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/joint_count_cast.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

struct RobotDescription;  // tpf/model/robot_description.hpp

/// The identified model: the rigid body in base parameters, the friction and the effects added by
/// diagnosis, all in SI (N·m). At Eigen::Dynamic, resize(n) sizes it for n joints.
template <typename S, int N>
struct NominalModel {
  Model<S, N> model;  ///< kinematics, URDF inertias, drives (torque_constant) from the robot file
  /// Identified rigid-body part (incl. armature): effort_rigid = Y(q,q̇,q̈).cols(base_columns)·
  /// base_values [N·m]. Only the first base_count entries count (13n entries are kept).
  int base_count = 0;
  std::conditional_t<N == Eigen::Dynamic, std::vector<int>,
                     std::array<int, std::size_t(N < 0 ? 0 : regressor_columns<N>)>>
      base_columns{};
  DynamicParameters<S, N> base_values = zero_or_empty<DynamicParameters<S, N>>();
  /// Stribeck + viscous + load dependence (α_c, α_v on |G_j(q)| of `model`), N·m. Per motor:
  /// where model.coupled, entry m is motor m's curve on its velocity (C·q̇)_m at the output scale
  /// (its load terms on |G_m|), acting on the joints through Cᵀ.
  StribeckParameters<S, N> friction;
  /// The memoryless effects diagnosis added (tpf/effects/added_effects.hpp). An unmodelled
  /// payload is folded into the base parameters; load-dependent, direction-asymmetric and
  /// neighbour-load friction into `friction`. Effects the run time cannot evaluate
  /// (OfflineOnlyEffects) are reported by diagnosis, not written, and a file holding them is
  /// refused.
  AddedEffects<S, N> added;

  /// Sizes everything but the model (make_model gives that) for n joints: no base parameters, no
  /// friction, no added effects.
  void resize(int n) {
    base_count = 0;
    resize_storage(base_columns, static_cast<std::size_t>(13 * n));
    base_values = DynamicParameters<S, N>::Zero(13 * n);
    friction.resize(n);
    added.resize(n);
  }
};

/// The same nominal model with joint count `To` (Eigen::Dynamic, or the model's own: tpf::Error
/// otherwise). Start-up code.
template <int To, typename S, int From>
NominalModel<S, To> joint_count_cast(const NominalModel<S, From>& from) {
  NominalModel<S, To> to;
  to.model = joint_count_cast<To>(from.model);
  const int n = from.model.joint_count();
  to.resize(n);
  to.base_count = from.base_count;
  std::copy(from.base_columns.begin(), from.base_columns.end(), to.base_columns.begin());
  to.base_values = from.base_values;
  to.friction = joint_count_cast<To, S>(from.friction);
  to.added.template assign<From>(from.added);
  return to;
}

/// Rigid-body effort of the base parameters, N·m: τ = Y(q,q̇,q̈).cols(base_columns)·base_values,
/// with the regressor computed into `Y` (scratch). Allocation-free.
template <typename S, int N>
JointVector<S, N> rigid_body_torque(const NominalModel<S, N>& nominal, Data<S, N>& data,
                                    Regressor<S, N>& Y, const NoDeduce<JointVector<S, N>>& q,
                                    const NoDeduce<JointVector<S, N>>& dq,
                                    const NoDeduce<JointVector<S, N>>& ddq) {
  compute_regressor(nominal.model, data, q, dq, ddq, Y);
  JointVector<S, N> tau = JointVector<S, N>::Zero(q.size());
  for (int i = 0; i < nominal.base_count; ++i)
    tau += Y.col(nominal.base_columns[i]) * nominal.base_values[i];
  return tau;
}

/// Torque of the added memoryless effects (RunTimeEffects, tpf/effects/) [N·m]:
/// τ_j = k_j q_j + c_j + Σ_k≠j (C_v,jk q̇_k + C_a,jk q̈_k) + Σ ripple terms of j. Allocation-free.
template <typename S, int N>
JointVector<S, N> added_effort(const NominalModel<S, N>& nominal,
                               const NoDeduce<JointVector<S, N>>& q,
                               const NoDeduce<JointVector<S, N>>& dq,
                               const NoDeduce<JointVector<S, N>>& ddq) noexcept(N !=
                                                                                Eigen::Dynamic) {
  return nominal.added.torque({q, dq, ddq, nominal.model.gear_ratio});
}

/// The nominal model in link form for the per-cycle path (computed once at start-up):
///   rigid = the identified base values scattered onto their regressor columns (zero elsewhere),
///           a standard parameter vector π with Y·π = Y_b·π_b for every motion (Y_b is made of
///           columns of Y), evaluated by link_parameter_torque.
/// The load-dependent friction's |G(q)| is that of nominal.model's own inertias (gravity_at_pose,
/// on the model's constants).
template <typename S, int N>
struct NominalLinks {
  LinkParameters<S, N> rigid;
  bool load_dependent = false;  ///< some α or neighbour-load β, γ ≠ 0: G(q) of the model is needed
  bool neighbour_load = false;  ///< some β, γ ≠ 0 (without one, those terms add zeros)
  bool added_effects = false;   ///< some added effect is present (without one, they add zeros)
};

/// NominalLinks of `nominal` (see there). Allocation-free at a fixed joint count; columns outside
/// 0..13n−1 are ignored.
template <typename S, int N>
NominalLinks<S, N> nominal_links(const NominalModel<S, N>& nominal) noexcept(N != Eigen::Dynamic) {
  const int columns = 13 * nominal.model.joint_count();
  DynamicParameters<S, N> pi = DynamicParameters<S, N>::Zero(columns);
  for (int i = 0; i < nominal.base_count; ++i) {
    const int c = nominal.base_columns[i];
    if (c >= 0 && c < columns) pi[c] += nominal.base_values[i];
  }
  NominalLinks<S, N> links;
  links.rigid = link_parameters<S, N>(pi);
  links.neighbour_load = has_neighbour_load(nominal.friction);
  links.load_dependent = (nominal.friction.load_coulomb.array() != S(0)).any() ||
                         (nominal.friction.load_viscous.array() != S(0)).any() ||
                         links.neighbour_load;
  links.added_effects = nominal.added.any();
  return links;
}

/// predict_effort on the link transforms already in data.liMi (joint_transforms or
/// forward_kinematics of nominal.model at q first; the world poses are not read): models of one
/// robot evaluated at one sample share one kinematics. The same operations, so the same result;
/// terms whose parameters are all zero (added effects, neighbour load; see NominalLinks) are not
/// evaluated. `scratch`: a vector of the joint count to work in (rigid, friction and scratch
/// sized for the model's joints). Allocation-free (at Eigen::Dynamic too), no exceptions.
template <typename S, int N>
void predict_effort_at_pose(const NominalModel<S, N>& nominal, const NominalLinks<S, N>& links,
                            Data<S, N>& data, const NoDeduce<JointVector<S, N>>& q,
                            const NoDeduce<JointVector<S, N>>& dq,
                            const NoDeduce<JointVector<S, N>>& ddq, JointVector<S, N>& rigid,
                            JointVector<S, N>& friction, JointVector<S, N>& scratch) noexcept {
  link_parameter_torque(nominal.model, links.rigid, data, dq, ddq, rigid);
  if (links.added_effects) {  // rigid += added_effort(nominal, q, dq, ddq)
    scratch.setZero();
    const EffectInput<S, N> x{q, dq, ddq, nominal.model.gear_ratio};
    nominal.added.for_each([&](const auto& effect) { effect.add_torque(x, scratch); });
    rigid += scratch;
  }
  const int n = nominal.model.joint_count();
  JointVector<S, N>& abs_gravity = scratch;
  abs_gravity.setZero();
  if (links.load_dependent) {
    // Element by element: data.g was just stored that way (a vector load of it would wait).
    const JointVector<S, N>& gravity = gravity_at_pose(nominal.model, data);
    for (int j = 0; j < n; ++j)
      abs_gravity[j] = std::abs(gravity[j]);
  }
  // stribeck_friction(nominal.friction, dq, |G|), or own_load_stribeck_friction without
  // neighbour load, element by element into `friction`.
  if (nominal.model.coupled) {  // motor m's curve on its velocity (C·q̇)_m, through Cᵀ
    friction.setZero();
    for (int m = 0; m < n; ++m) {
      const S v = nominal.model.motor_rate(m, dq);
      S f = stribeck_friction(nominal.friction, m, v, abs_gravity[m]);
      if (links.neighbour_load) f += neighbour_load_friction(nominal.friction, m, v, abs_gravity);
      nominal.model.add_motor_torque(m, f, friction);
    }
  } else if (links.neighbour_load) {
    for (int j = 0; j < n; ++j)
      friction[j] = stribeck_friction(nominal.friction, j, dq[j], abs_gravity[j]) +
                    neighbour_load_friction(nominal.friction, j, dq[j], abs_gravity);
  } else {
    for (int j = 0; j < n; ++j)
      friction[j] = stribeck_friction(nominal.friction, j, dq[j], abs_gravity[j]);
  }
}

/// The same with its scratch on the stack (allocated at Eigen::Dynamic).
template <typename S, int N>
void predict_effort_at_pose(const NominalModel<S, N>& nominal, const NominalLinks<S, N>& links,
                            Data<S, N>& data, const NoDeduce<JointVector<S, N>>& q,
                            const NoDeduce<JointVector<S, N>>& dq,
                            const NoDeduce<JointVector<S, N>>& ddq, JointVector<S, N>& rigid,
                            JointVector<S, N>& friction) noexcept(N != Eigen::Dynamic) {
  const int n = nominal.model.joint_count();
  JointVector<S, N> scratch;
  scratch.resize(n);
  rigid.resize(n);
  friction.resize(n);
  predict_effort_at_pose(nominal, links, data, q, dq, ddq, rigid, friction, scratch);
}

/// Predicted effort (joint torque the drive must produce) [N·m], split in two:
///   rigid    = Y_b(q,q̇,q̈)·π_b + added(q,q̇,q̈)
///              (rigid body incl. armature, plus ripple, spring, offset and coupling when added),
///   friction = stribeck_friction(nominal.friction, q̇, |G(q)|): Stribeck + viscous with load
///              dependence, direction asymmetry and neighbour load (see StribeckParameters),
///              G = G(q) of nominal.model [N·m], sgn(0) = 0: at rest the sliding friction is not
///              predicted (it is whatever the drive settled at; the estimator's FSM handles it).
/// The per-cycle form: one forward kinematics (left in data.liMi / data.oMi at q), Y_b·π_b by
/// Newton–Euler on the link form `links` = nominal_links(nominal) (equal to the regressor form to
/// rounding), and G(q) by a gravity-only pass (gravity_at_pose) when the friction is load
/// dependent.
/// Allocation-free, no exceptions.
template <typename S, int N>
void predict_effort(const NominalModel<S, N>& nominal, const NominalLinks<S, N>& links,
                    Data<S, N>& data, const NoDeduce<JointVector<S, N>>& q,
                    const NoDeduce<JointVector<S, N>>& dq, const NoDeduce<JointVector<S, N>>& ddq,
                    JointVector<S, N>& rigid,
                    JointVector<S, N>& friction) noexcept(N != Eigen::Dynamic) {
  forward_kinematics(nominal.model, data, q);
  predict_effort_at_pose(nominal, links, data, q, dq, ddq, rigid, friction);
}

/// predict_effort with the link form built on the spot (a few dozen copies): for offline callers
/// that evaluate a model once; a per-cycle caller keeps nominal_links(nominal) instead.
template <typename S, int N>
void predict_effort(const NominalModel<S, N>& nominal, Data<S, N>& data,
                    const NoDeduce<JointVector<S, N>>& q, const NoDeduce<JointVector<S, N>>& dq,
                    const NoDeduce<JointVector<S, N>>& ddq, JointVector<S, N>& rigid,
                    JointVector<S, N>& friction) {
  predict_effort(nominal, nominal_links(nominal), data, q, dq, ddq, rigid, friction);
}

/// The regressor form of predict_effort (the reference the link form is tested against, and the
/// form identification fits): Y_b·π_b from compute_regressor, G(q) by compute_gravity.
template <typename S, int N>
void predict_effort_by_regressor(const NominalModel<S, N>& nominal, Data<S, N>& data,
                                 const NoDeduce<JointVector<S, N>>& q,
                                 const NoDeduce<JointVector<S, N>>& dq,
                                 const NoDeduce<JointVector<S, N>>& ddq, JointVector<S, N>& rigid,
                                 JointVector<S, N>& friction) {
  Regressor<S, N> Y;
  rigid = rigid_body_torque(nominal, data, Y, q, dq, ddq) + added_effort(nominal, q, dq, ddq);
  const JointVector<S, N> abs_gravity = compute_gravity(nominal.model, data, q).cwiseAbs();
  if (!nominal.model.coupled) {
    friction = stribeck_friction(nominal.friction, dq, abs_gravity);
    return;
  }
  const JointVector<S, N> motor_dq = nominal.model.coupling * dq;
  friction = nominal.model.coupling.transpose() *
             stribeck_friction(nominal.friction, motor_dq, abs_gravity);
}

/// Name of standard regressor column c (0-based) of an N-joint arm: per link k (1..N) "m<k>",
/// "mx<k>", "my<k>", "mz<k>", "Ixx<k>", "Ixy<k>", "Ixz<k>", "Iyy<k>", "Iyz<k>", "Izz<k>"
/// (first moments and inertia about the link origin), then "Ia<j>" (armature), "fc<j>"
/// (Coulomb), "fv<j>" (viscous).
std::string regressor_column_name(int joints, int column);

/// The start-up code below works at the run-time joint count (Eigen::Dynamic); each function has
/// a header-only form for a program of N joints that converts (joint_count_cast).
using NominalModelX = NominalModel<double, Eigen::Dynamic>;

/// A nominal model whose rigid body is the robot model itself (base parameters β·π of the model's
/// inertias and armature) and whose friction is `friction`: the "true" model of the digital twin
/// when given the twin's robot and friction, or the starting point before identification.
/// Start-up code (allocates).
NominalModelX nominal_from_model(const Model<double, Eigen::Dynamic>& model,
                                 const StribeckParameters<double, Eigen::Dynamic>& friction);

/// Loads a parameter file (JSON, "format": "tpf-params", "version": 2, torques in N·m) written by
/// `tpf identify` / `tpf diagnose`, with the robot file it was identified for. Start-up code:
/// throws tpf::Error "file: field: reason" on a version-1 file (efforts in the log's unit; `tpf
/// upgrade` converts it), a missing/unknown field, a wrong size, a joint count that differs
/// from the robot file's (or from `joints` when that is > 0), an unknown base parameter name, a
/// non-finite or out-of-range value, or an effect the run time cannot evaluate (non-zero
/// thermal_viscous or effort_lead_s, named in the message).
NominalModelX load_nominal_model(const std::filesystem::path& params_file,
                                 const std::filesystem::path& robot_file, int joints = 0);
/// The same with the robot file already loaded (load_robot_description).
NominalModelX load_nominal_model(const std::filesystem::path& params_file,
                                 const RobotDescription& robot, int joints = 0);

/// Writes a parameter file (atomically: temporary + rename). `fit_quality_json` (a JSON object's
/// text, may be empty) is stored under "fit" for people and scripts; `source` (e.g. the log path)
/// under "source". Throws tpf::Error on I/O failure or bad JSON text.
void save_nominal_model(const std::filesystem::path& params_file, const NominalModelX& nominal,
                        const std::string& source = "", const std::string& fit_quality_json = "");

/// The rigid-body base parameters (inertial + armature columns 0..11n−1 of the regressor) of a
/// model's kinematics: find_base_parameters on regressors stacked at 200 seeded random states
/// within the joint limits (or ±π). Deterministic. Start-up/offline code.
BaseParameters rigid_body_base_parameters(const Model<double, Eigen::Dynamic>& model);

/// nominal_from_model for a program of N joints.
template <int N>
NominalModel<double, N> nominal_from_model(const Model<double, N>& model,
                                           const StribeckParameters<double, N>& friction) {
  return joint_count_cast<N>(nominal_from_model(
      joint_count_cast<Eigen::Dynamic>(model), joint_count_cast<Eigen::Dynamic, double>(friction)));
}

/// load_nominal_model for a program of N joints: the file must be of an N-joint arm.
template <int N>
NominalModel<double, N> load_nominal_model(const std::filesystem::path& params_file,
                                           const std::filesystem::path& robot_file) {
  return joint_count_cast<N>(load_nominal_model(params_file, robot_file, N));
}
template <int N>
NominalModel<double, N> load_nominal_model(const std::filesystem::path& params_file,
                                           const RobotDescription& robot) {
  return joint_count_cast<N>(load_nominal_model(params_file, robot, N));
}

/// save_nominal_model of an N-joint program's model.
template <int N>
void save_nominal_model(const std::filesystem::path& params_file,
                        const NominalModel<double, N>& nominal, const std::string& source = "",
                        const std::string& fit_quality_json = "") {
  save_nominal_model(params_file, joint_count_cast<Eigen::Dynamic>(nominal), source,
                     fit_quality_json);
}

/// rigid_body_base_parameters of an N-joint program's model.
template <int N>
BaseParameters rigid_body_base_parameters(const Model<double, N>& model) {
  return rigid_body_base_parameters(joint_count_cast<Eigen::Dynamic>(model));
}

}  // namespace tpf
