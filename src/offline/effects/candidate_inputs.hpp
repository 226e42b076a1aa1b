// What the candidate library needs from a first fit of the declared model.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace tpf::offline {

/// A motor of an adjacent pair of joints (i, i + 1), both declared uncoupled, turning with
/// a·q_i + b·q_{i+1} (max(|a|, |b|) = 1): the ratio fitted to the declared model's residual
/// (fit_coupled_motors). Its friction and rotor act on joint i with a share a and on joint i + 1
/// with b (τ_joint = Cᵀ·τ_motor).
struct CoupledMotorCandidate {
  int joint = 0;                  ///< i, 0-based: the pair (i, i + 1)
  double a = 0.0, b = 1.0;        ///< the motor's velocity a·q̇_i + b·q̇_{i+1}
  bool armature = false;          ///< its rotor's column through C is outside the rigid body's span
  double static_velocity = 1e-4;  ///< below it the motor's direction is 0 (rad/s)

  /// The motor's own joint (the one of share 1) and the ratio c of the other: the motor of joint
  /// `own()` turns with q_own + c·q_other. The friction cannot tell it from the other joint's
  /// motor turning with q_other + q_own/c: named with |c| ≤ 1.
  int own() const { return std::abs(b) >= std::abs(a) ? joint + 1 : joint; }
  int other() const { return own() == joint ? joint + 1 : joint; }
  double ratio() const { return std::abs(b) >= std::abs(a) ? a / b : b / a; }
};

struct CandidateInputs {
  bool enabled = false;
  Eigen::VectorXd ripple_cycles;  ///< per joint: periods per output revolution (real), 0 = none
  Eigen::VectorXd ripple_motor_cycles;  ///< per joint: periods per motor revolution, 0 = none
  /// Per joint: the periods of ripple_cycles (ripple_motor_cycles) within the joint's range of
  /// motion; under 1 the candidate names no frequency and is ambiguous with its joint's offset
  /// and spring. Empty: every period in view.
  Eigen::VectorXd ripple_periods, ripple_motor_periods;
  /// The delay candidate's column per sample and joint, the declared prediction's difference
  /// quotient over effort_lag_s (search_effort_lag), or empty.
  Eigen::MatrixXd prediction_rate;
  double effort_lag_s = 0.0;
  Eigen::MatrixXd abs_gravity;  ///< |G_j(q)| per sample and joint [N·m] (gravity_load)
  /// Per joint: the other joint whose load |G_k| its neighbour-load candidate takes
  /// (choose_neighbour_loads), −1 = none; empty = no neighbour-load candidate.
  Eigen::VectorXi neighbour_load_source;
  double reference_temperature = 25.0;  ///< °C
  /// Per joint: the declared fit's viscous coefficient b_j [N·m·s/rad], which the
  /// every-joint thermal candidate scales; empty = no every-joint thermal candidate.
  Eigen::VectorXd viscous;
  /// Per joint: 1 when its effort channel is dead (LogChecks::dead_joints): no candidate of that
  /// joint, nor of a pair holding it, is offered. Empty: none.
  std::vector<char> dead_joints;
  /// Coupled-motor candidates (CoupledMotorColumns), one per adjacent pair of uncoupled motors.
  std::vector<CoupledMotorCandidate> coupled_motors;
};

}  // namespace tpf::offline
