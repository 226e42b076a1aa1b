// The true rigid-body arm of the twin: the scenario's robot model (with armature), optionally an
// undeclared payload on the last link, its pads, and the dynamics calls the simulator needs.
// A robot file that couples motors (coupled_to) gives the model's coupling C (motors × joints):
// the core's M(q) then holds the rotors as Cᵀ·diag(armature)·C (armature = J_m·r², reflected to
// the output), and the plant and drives take each motor on its coordinate (C·q)_m.
// A thin adapter over tpf::core's model and algorithms at a run-time joint count
// (N = Eigen::Dynamic): one compiled twin for robots of any joint count. Its solves and 3×N
// products are the twin's own (twin_linear_algebra.hpp), which round as Eigen does at a fixed
// joint count.
#pragma once

#include <string>
#include <vector>

#include "offline/sim/scenario.hpp"
#include "offline/sim/twin_linear_algebra.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"
#include "tpf/skin/pad_layout.hpp"

namespace tpf::offline {

/// A pad in world coordinates at one configuration.
struct PadFrame {
  int link = 0;                                      ///< 1..N
  Vector3<double> centre = Vector3<double>::Zero();  ///< world, m
  Matrix3<double> rotation =
      Matrix3<double>::Identity();  ///< columns: tangent x, tangent y, normal
  /// ∂centre/∂q, world frame, 3×N.
  TwinJacobian linear_jacobian;
};

class TwinArm {
 public:
  /// Loads robot and pads; adds the payload when enabled; zeroes gravity when disabled.
  /// Throws tpf::Error naming the robot file when it has no joint.
  explicit TwinArm(const Scenario& scenario);

  /// q̈ = M⁻¹(τ − C(q,q̇)q̇ − G(q)).
  TwinVector forward_dynamics(const TwinVector& q, const TwinVector& dq,
                              const TwinVector& tau) const;
  /// q̈ = M⁻¹(τ − C(q,q̇)q̇ − G(q)) into `ddq` (resized to N): the same values as the by-value
  /// call, allocation-free once `ddq` has N entries and the arm has made one such call. `ddq`
  /// must not be `q`, `dq` or `tau`.
  void forward_dynamics(const TwinVector& q, const TwinVector& dq, const TwinVector& tau,
                        TwinVector& ddq) const;
  /// M(q), armature on the diagonal. The reference is to the arm's workspace: the next dynamics
  /// call on this arm (mass_matrix, gravity, forward_dynamics, energy, pad_frame) overwrites it,
  /// so copy what you keep. Allocation-free.
  const TwinMatrix& mass_matrix(const TwinVector& q) const;
  /// G(q), N·m; in the arm's workspace like mass_matrix (copy what you keep). Allocation-free.
  const TwinVector& gravity(const TwinVector& q) const;
  /// T + V, J.
  double energy(const TwinVector& q, const TwinVector& dq) const;
  /// Pad k (0-based) at q.
  PadFrame pad_frame(const TwinVector& q, int k) const;
  /// Pad k at q into `frame`: allocation-free once `frame` has been filled for this arm.
  void pad_frame(const TwinVector& q, int k, PadFrame& frame) const;
  /// Velocity of a pad's centre, J_v·q̇ (world frame, m/s).
  Vector3<double> pad_velocity(const PadFrame& frame, const TwinVector& dq) const;
  int pad_count() const;
  /// Joint count N of the robot.
  int joints() const;
  /// The robot's name (robot file, else URDF).
  const std::string& name() const;
  /// Pad area from the layout, cm².
  double pad_area_cm2(int k) const;

  const TwinVector& torque_constant() const;  ///< N·m/A, output side
  const TwinVector& current_limit() const;    ///< A
  const TwinVector& velocity_limit() const;   ///< rad/s
  const TwinVector& lower() const;
  const TwinVector& upper() const;
  /// The transmission's coupling C (motors × joints, Model::coupling): motor m turns with
  /// (C·q)_m at the output scale and its torque acts on the joints through Cᵀ. The identity
  /// unless the robot file couples motors.
  const TwinMatrix& coupling() const;
  /// Whether C differs from the identity (a coupled_to in the robot file).
  bool coupled() const;

 private:
  Model<double, Eigen::Dynamic> model_;
  mutable Data<double, Eigen::Dynamic> data_;          ///< workspace of the dynamics calls
  mutable TwinCholesky mass_factor_;                   ///< of M(q), forward_dynamics
  mutable Jacobian<double, Eigen::Dynamic> jacobian_;  ///< pad_frame's 6×N point Jacobian
  TwinVector zero_;  ///< N zeros: forward_dynamics's q̈ of the RNEA
  std::vector<Pad> pads_;
  TwinVector current_limit_a_;
};

}  // namespace tpf::offline
