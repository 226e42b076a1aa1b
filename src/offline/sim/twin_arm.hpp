// The true rigid-body arm of the twin: the robot model of data/ (with armature), optionally an
// undeclared payload on the last link, its pads, and the dynamics calls the simulator needs.
// A thin adapter over tpf::core's model and algorithms.
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
  Eigen::Matrix<double, 3, kTwinJoints> linear_jacobian =
      Eigen::Matrix<double, 3, kTwinJoints>::Zero();  ///< ∂centre/∂q, world frame
};

class TwinArm {
 public:
  /// Loads robot and pads; adds the payload when enabled; zeroes gravity when disabled.
  TwinArm(const Scenario& scenario);
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
  int pad_count() const;
  /// Pad area from the layout, cm².
  double pad_area_cm2(int k) const;

  const TwinVector& torque_constant() const;  ///< N·m/A, output side
  const TwinVector& current_limit() const;    ///< A
  const TwinVector& velocity_limit() const;   ///< rad/s
  const TwinVector& lower() const;
  const TwinVector& upper() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tpf::offline
