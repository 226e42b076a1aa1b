// Model of the DYNAMIXEL-P PH54 drive in position mode: a cascade of a position P loop, a
// velocity PI loop and a current limit, followed by the current loop (first-order lag). Because
// the velocity loop integrates, the current at rest is whatever the integrator settled at, which
// depends on the direction of approach, on the load and on the friction state.
//
//   v_cmd = f_ff·q̇_ref + K_p·(q_ref − q),   clamped to ±velocity limit
//   i_cmd = K_v·(v_cmd − q̇) + ∫ K_i·(v_cmd − q̇) dt,   clamped to ±current limit
//   τ_i·di/dt = i_cmd − i
// Gains from bandwidths: K_p = 2π f_p; K_v = 2π f_v·J/K_t; K_i = 2π f_i·K_v. Currents in A.
// The cascade is the PH54's; the twin runs it for any robot, with each joint's inertia, torque
// constant and current limit from the robot file.
#pragma once

#include "offline/sim/scenario.hpp"

namespace tpf::offline {

class Ph54Drive {
 public:
  /// `inertia` J per joint (kg·m², output side, armature included), `torque_constant` K_t
  /// (N·m/A), `current_limit` (A), `velocity_limit` (rad/s).
  Ph54Drive(const DriveConfig& config, const TwinVector& inertia, const TwinVector& torque_constant,
            const TwinVector& current_limit, const TwinVector& velocity_limit);

  /// One control period of length dt with the drive's own measurements (quantised position and
  /// velocity); returns the actual motor current i (A) after the current loop.
  const TwinVector& update(const TwinVector& q_ref, const TwinVector& dq_ref, const TwinVector& q,
                           const TwinVector& dq, double dt);

  /// Starts the loops at rest holding `current` (A) in the integrators (e.g. gravity).
  void reset(const TwinVector& current);

  const TwinVector& current() const { return current_; }
  const TwinVector& position_gain() const { return kp_; }
  const TwinVector& velocity_gain() const { return kv_; }
  const TwinVector& integral_gain() const { return ki_; }

 private:
  DriveConfig config_;
  TwinVector kp_, kv_, ki_, current_limit_, velocity_limit_;
  TwinVector integral_, current_;
};

}  // namespace tpf::offline
