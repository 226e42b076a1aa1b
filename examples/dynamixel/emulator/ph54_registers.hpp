// One emulated PH54's control table with the access rules the host relies on: EEPROM only with
// torque off, read-only registers, the bus-watchdog lock on goal registers, goal-current limit.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "dynamixel/emulator/motor_plant.hpp"
#include "dynamixel/protocol/packet.hpp"

namespace tpf::dxl::emu {

class Ph54Registers {
 public:
  /// Defaults of the e-manual for `model` (2020 or 2010), ID and firmware version.
  Ph54Registers(std::uint8_t id, std::uint16_t model, std::uint8_t firmware);

  /// Reads `out.size()` bytes at `address`; error number if out of the table.
  StatusError read(std::uint16_t address, std::span<std::uint8_t> out) const;
  /// Applies a Write; returns the status error (Access, Data Range, Data Limit) and leaves the
  /// table unchanged on error.
  StatusError write(std::uint16_t address, std::span<const std::uint8_t> data);

  /// ERR byte of every status: Alert while Hardware Error Status ≠ 0.
  StatusError alert_bits() const;
  /// Goal for the plant from Operating Mode, Torque Enable and the goal registers.
  MotorGoal goal() const;
  /// Present Current/Velocity/Position, quantised to the register units, and Realtime Tick.
  void set_present(const MotorState& state, std::uint16_t tick_ms);
  /// Hardware error (e.g. Overload): Alert on every status, torque off, until Reboot.
  void raise_hardware_error(std::uint8_t bits);
  /// Reboot (0x08): clears the hardware error, torque off.
  void reboot();
  /// Bus watchdog: called with the time since the last instruction; trips to 0xFF (−1).
  void check_watchdog(double idle_s);

  std::uint8_t id() const { return u8(ph54::id); }
  std::uint8_t u8(std::uint16_t address) const { return table_[address]; }
  std::uint32_t u32(std::uint16_t address, std::size_t size) const;

 private:
  void set(std::uint16_t address, std::uint32_t value, std::size_t size);

  std::array<std::uint8_t, 1024> table_{};
};

}  // namespace tpf::dxl::emu
