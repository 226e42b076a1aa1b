#include "dynamixel/emulator/first_order_plant.hpp"

#include <algorithm>
#include <cmath>

namespace tpf::dxl::emu {
namespace {

/// Exact discretisation of τ·dx/dt = target − x over dt.
double lag(double x, double target, double tau, double dt) {
  return target + (x - target) * std::exp(-dt / tau);
}

}  // namespace

FirstOrderPlant::FirstOrderPlant(std::size_t joints, FirstOrderPlantParams params)
    : params_(params), states_(joints) {}

void FirstOrderPlant::step(double dt, std::span<const MotorGoal> goals) {
  const FirstOrderPlantParams& p = params_;
  for (std::size_t k = 0; k < states_.size() && k < goals.size(); ++k) {
    MotorState& s = states_[k];
    const MotorGoal& g = goals[k];
    using Mode = ph54::OperatingMode;
    if (!g.torque_enabled) {
      s.current_A = 0.0;
      s.velocity_rad_s = lag(s.velocity_rad_s, 0.0, p.tau_velocity_s, dt);
    } else if (g.mode == Mode::current) {
      s.current_A = lag(s.current_A, g.current_A, p.tau_current_s, dt);
      s.velocity_rad_s =
          lag(s.velocity_rad_s, p.velocity_per_ampere * s.current_A, p.tau_velocity_s, dt);
    } else if (g.mode == Mode::velocity) {
      s.velocity_rad_s = lag(s.velocity_rad_s, g.velocity_rad_s, p.tau_velocity_s, dt);
      s.current_A = s.velocity_rad_s / p.velocity_per_ampere;
    } else {  // position, extended position (PWM treated as position hold)
      s.velocity_rad_s = std::clamp((g.position_rad - s.position_rad) / p.tau_position_s,
                                    -p.max_velocity_rad_s, p.max_velocity_rad_s);
      s.current_A = s.velocity_rad_s / p.velocity_per_ampere;
    }
    if (g.torque_enabled && g.mode != Mode::current && g.current_A > 0.0)
      s.current_A = std::clamp(s.current_A, -g.current_A, g.current_A);
    s.position_rad += s.velocity_rad_s * dt;
  }
}

}  // namespace tpf::dxl::emu
