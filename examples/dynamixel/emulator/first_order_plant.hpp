// Default plant: independent joints, each a first-order lag towards its goal.
//   current mode:  τ_i·di/dt = i_goal − i,   τ_v·dv/dt = k_v·i − v
//   velocity mode: τ_v·dv/dt = v_goal − v,   i = v / k_v
//   position mode: v = clamp((q_goal − q)/τ_q, ±v_max),   i = v / k_v
//   torque off:    τ_v·dv/dt = −v,  i = 0;   always dq/dt = v.
#pragma once

#include <vector>

#include "dynamixel/emulator/motor_plant.hpp"

namespace tpf::dxl::emu {

struct FirstOrderPlantParams {
  double tau_current_s = 0.002;
  double tau_velocity_s = 0.05;
  double tau_position_s = 0.1;
  double velocity_per_ampere = 1.0;  ///< k_v [rad/s per A] (steady state, no load)
  double max_velocity_rad_s = 3.0;   ///< ≈ 29 rpm
};

class FirstOrderPlant final : public MotorPlant {
 public:
  FirstOrderPlant(std::size_t joints, FirstOrderPlantParams params = {});

  std::size_t joints() const override { return states_.size(); }
  void step(double dt, std::span<const MotorGoal> goals) override;
  MotorState state(std::size_t k) const override { return states_[k]; }
  /// Sets joint k's state (test set-up).
  void set_state(std::size_t k, const MotorState& s) { states_[k] = s; }

 private:
  FirstOrderPlantParams params_;
  std::vector<MotorState> states_;
};

}  // namespace tpf::dxl::emu
