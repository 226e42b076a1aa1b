#include "dynamixel/emulator/ph54_registers.hpp"

#include <algorithm>

#include "dynamixel/ph54/units.hpp"

namespace tpf::dxl::emu {

using namespace ph54;

Ph54Registers::Ph54Registers(std::uint8_t motor_id, std::uint16_t model, std::uint8_t firmware) {
  const bool big = model == kModelPh54_200;
  set(model_number, model, 2);
  set(firmware_version, firmware, 1);
  set(ph54::id, motor_id, 1);
  set(baud_rate, static_cast<std::uint8_t>(BaudCode::b57600), 1);
  set(return_delay_time, 250, 1);
  set(operating_mode, static_cast<std::uint8_t>(OperatingMode::position), 1);
  set(current_limit, big ? 22740 : 15900, 2);
  set(velocity_limit, big ? 2900 : 2920, 4);
  set(max_position_limit, 501433, 4);
  set(min_position_limit, static_cast<std::uint32_t>(-501433), 4);
  set(shutdown, 52, 1);
  set(516, 2, 1);  // Status Return Level: all
  set(goal_current, big ? 22740 : 15900, 2);
  set(present_input_voltage, 240, 2);
  set(present_temperature, 35, 1);
}

std::uint32_t Ph54Registers::u32(std::uint16_t address, std::size_t size) const {
  return get_le(std::span(table_).subspan(address, size));
}

void Ph54Registers::set(std::uint16_t address, std::uint32_t value, std::size_t size) {
  put_le(std::span(table_).subspan(address, size), value);
}

StatusError Ph54Registers::read(std::uint16_t address, std::span<std::uint8_t> out) const {
  if (out.empty() || address + out.size() > table_.size()) return {StatusError::access};
  std::copy_n(table_.begin() + address, out.size(), out.begin());
  return alert_bits();
}

StatusError Ph54Registers::write(std::uint16_t address, std::span<const std::uint8_t> data) {
  const std::size_t end = address + data.size();
  const auto touches = [&](std::uint16_t a, std::size_t n) { return address < a + n && end > a; };
  StatusError status = alert_bits();
  if (data.empty() || end > table_.size()) return {std::uint8_t(status.raw | StatusError::access)};
  const bool read_only =
      touches(0, 7) || touches(hardware_error_status, 1) || touches(realtime_tick, 42);
  const bool eeprom_locked = address < kEepromEnd && u8(torque_enable) != 0;
  if (read_only || eeprom_locked) return {std::uint8_t(status.raw | StatusError::access)};
  const bool goal = touches(goal_current, 18);  // 548..565: goal PWM … goal position
  if (goal && u8(bus_watchdog) == 0xFF) return {std::uint8_t(status.raw | StatusError::data_range)};
  std::array<std::uint8_t, 1024> next = table_;
  std::copy(data.begin(), data.end(), next.begin() + address);
  const auto limit = static_cast<std::int32_t>(get_le(std::span(next).subspan(current_limit, 2)));
  const auto current = static_cast<std::int16_t>(get_le(std::span(next).subspan(goal_current, 2)));
  if (touches(goal_current, 2) && std::abs(current) > limit)
    return {std::uint8_t(status.raw | StatusError::data_limit)};
  if (touches(torque_enable, 1) && data[torque_enable - address] != 0 &&
      u8(hardware_error_status) != 0)
    return {std::uint8_t(status.raw | StatusError::access)};  // locked until Reboot
  table_ = next;
  return status;
}

StatusError Ph54Registers::alert_bits() const {
  return {std::uint8_t(u8(hardware_error_status) != 0 ? StatusError::kAlert : 0)};
}

MotorGoal Ph54Registers::goal() const {
  MotorGoal g;
  g.mode = static_cast<OperatingMode>(u8(operating_mode));
  g.torque_enabled = u8(torque_enable) != 0 && u8(bus_watchdog) != 0xFF;
  g.current_A = current_to_ampere(static_cast<std::int16_t>(u32(goal_current, 2)));
  g.velocity_rad_s = velocity_to_rad_s(static_cast<std::int32_t>(u32(goal_velocity, 4)));
  g.position_rad = position_to_rad(static_cast<std::int32_t>(u32(goal_position, 4)));
  return g;
}

void Ph54Registers::set_present(const MotorState& s, std::uint16_t tick_ms) {
  set(present_current, static_cast<std::uint16_t>(ampere_to_current(s.current_A)), 2);
  set(present_velocity, static_cast<std::uint32_t>(rad_s_to_velocity(s.velocity_rad_s)), 4);
  set(present_position, static_cast<std::uint32_t>(rad_to_position(s.position_rad)), 4);
  set(realtime_tick, tick_ms % 32768, 2);
}

void Ph54Registers::raise_hardware_error(std::uint8_t bits) {
  set(hardware_error_status, bits, 1);
  set(torque_enable, 0, 1);
}

void Ph54Registers::reboot() {
  set(hardware_error_status, 0, 1);
  set(torque_enable, 0, 1);
  set(bus_watchdog, 0, 1);
}

void Ph54Registers::check_watchdog(double idle_s) {
  const std::uint8_t w = u8(bus_watchdog);
  if (w != 0 && w != 0xFF && u8(torque_enable) != 0 && idle_s > w * 0.020)
    set(bus_watchdog, 0xFF, 1);
}

}  // namespace tpf::dxl::emu
