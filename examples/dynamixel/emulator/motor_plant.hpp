// What drives an emulated PH54 chain: the joints' physics behind the control table. The default
// is FirstOrderPlant; the digital-twin simulator can implement the same interface.
#pragma once

#include <cstddef>
#include <span>

#include "dynamixel/ph54/control_table.hpp"

namespace tpf::dxl::emu {

/// One motor's command, decoded from its control table (SI units, output side).
struct MotorGoal {
  ph54::OperatingMode mode = ph54::OperatingMode::position;
  bool torque_enabled = false;  ///< false: the motor coasts to a stop and draws no current
  double current_A = 0.0;       ///< Goal Current; also the current limit in velocity/position mode
  double velocity_rad_s = 0.0;  ///< Goal Velocity
  double position_rad = 0.0;    ///< Goal Position
};

/// One motor's measurable state (SI units, output side); quantised by the emulator.
struct MotorState {
  double position_rad = 0.0;
  double velocity_rad_s = 0.0;
  double current_A = 0.0;
};

/// The chain's physics. step() advances every joint together (a multibody model may couple them).
class MotorPlant {
 public:
  virtual ~MotorPlant() = default;
  /// Number of joints (= motors, in ID order).
  virtual std::size_t joints() const = 0;
  /// Advances the plant by dt seconds under goals[0..joints()).
  virtual void step(double dt, std::span<const MotorGoal> goals) = 0;
  /// State of joint k after the last step.
  virtual MotorState state(std::size_t k) const = 0;
};

}  // namespace tpf::dxl::emu
