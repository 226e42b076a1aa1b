// The true rigid-body arm of the twin: the scenario's robot model (with armature), optionally an
// undeclared payload on the last link, its pads, and the dynamics calls the simulator needs.
// A thin adapter over tpf::core's model and algorithms, which take the joint count N at compile
// time: twin_arm.cpp instantiates them once per N = 1..kTwinMaxJoints behind this class, the
// only place of the twin that knows N at compile time.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "offline/sim/scenario.hpp"

namespace tpf::offline {

/// A pad in world coordinates at one configuration.
struct PadFrame {
  int link = 0;                                      ///< 1..N
  Vector3<double> centre = Vector3<double>::Zero();  ///< world, m
  Matrix3<double> rotation =
      Matrix3<double>::Identity();  ///< columns: tangent x, tangent y, normal
  /// ∂centre/∂q, world frame, 3×N.
  Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, kTwinMaxJoints> linear_jacobian;
};

class TwinArm {
 public:
  /// Loads robot and pads; adds the payload when enabled; zeroes gravity when disabled.
  /// Throws tpf::Error naming the robot file when its joint count is outside 1..kTwinMaxJoints.
  explicit TwinArm(const Scenario& scenario);
  ~TwinArm();
  TwinArm(const TwinArm&);
  TwinArm& operator=(const TwinArm&);

  /// q̈ = M⁻¹(τ − C(q,q̇)q̇ − G(q)).
  TwinVector forward_dynamics(const TwinVector& q, const TwinVector& dq,
                              const TwinVector& tau) const;
  /// M(q), armature on the diagonal.
  TwinMatrix mass_matrix(const TwinVector& q) const;
  /// G(q), N·m.
  TwinVector gravity(const TwinVector& q) const;
  /// T + V, J.
  double energy(const TwinVector& q, const TwinVector& dq) const;
  /// Pad k (0-based) at q.
  PadFrame pad_frame(const TwinVector& q, int k) const;
  /// Velocity of a pad's centre, J_v·q̇ (world frame, m/s).
  Vector3<double> pad_velocity(const PadFrame& frame, const TwinVector& dq) const;
  /// A⁻¹·b for a symmetric positive definite N×N matrix A (Eigen's LDLT). Like the dynamics it
  /// runs at the robot's compile-time size: Eigen's LDLT and 3×N products round differently at
  /// run-time sizes, and the twin's logs must not depend on how its vectors are sized.
  TwinVector solve_spd(const TwinMatrix& a, const TwinVector& b) const;
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

  struct Impl;  ///< the rigid-body model at the robot's compile-time joint count (twin_arm.cpp)

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace tpf::offline
