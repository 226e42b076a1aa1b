#include "dynamixel/ph54/chain_setup.hpp"

#include <string>

#include "tpf/common/error.hpp"

namespace tpf::dxl::ph54 {
namespace {

std::string motor_name(std::uint8_t id) {
  return "dynamixel id " + std::to_string(id);
}

/// Start-up transactions are retried: a single lost or corrupted status must not abort it.
constexpr int kAttempts = 3;

/// Register write that must succeed with no error status.
void write_register(Bus& bus, std::uint8_t id, std::uint16_t address,
                    std::span<const std::uint8_t> data, const char* field) {
  StatusError error{};
  CommResult r = CommResult::rx_timeout;
  for (int attempt = 0; attempt < kAttempts && r != CommResult::success; ++attempt)
    r = bus.write(id, address, data, error);
  if (r != CommResult::success)
    throw Error::at(motor_name(id), 0, field, std::string("write failed: ") + to_string(r));
  if (error.number() != StatusError::none)
    throw Error::at(motor_name(id), 0, field,
                    "write refused with error number " + std::to_string(error.number()));
}

void write_u8(Bus& bus, std::uint8_t id, std::uint16_t address, std::uint8_t value,
              const char* field) {
  const std::uint8_t data[] = {value};
  write_register(bus, id, address, data, field);
}

/// Current mode: Goal Current = 0; velocity mode: Goal Velocity = 0 (torque still off). The goal
/// registers hold their power-on value (the emulator's Goal Current = Current Limit) or the last
/// run's goal while the motor stays powered, and Torque Enable = 1 drives towards it at once.
void write_neutral_goal(Bus& bus, std::uint8_t id, OperatingMode mode) {
  const std::uint8_t zero[4] = {};
  if (mode == OperatingMode::current)
    write_register(bus, id, goal_current, std::span(zero).first(2), "goal current");
  else if (mode == OperatingMode::velocity)
    write_register(bus, id, goal_velocity, zero, "goal velocity");
}

}  // namespace

ChainInfo set_up_chain(Bus& bus, const ChainConfig& config) {
  ChainInfo chain;
  chain.fast_sync_read = !config.ids.empty();
  for (const std::uint8_t id : config.ids) {
    PingInfo ping;
    CommResult r = CommResult::rx_timeout;
    for (int attempt = 0; attempt < kAttempts && r != CommResult::success; ++attempt)
      r = bus.ping(id, ping);
    if (r != CommResult::success)
      throw Error::at(motor_name(id), 0, "ping", std::string("no answer: ") + to_string(r));
    if (ping.model != kModelPh54_200 && ping.model != kModelPh54_100)
      throw Error::at(motor_name(id), 0, "model number",
                      std::to_string(ping.model) + " is not a PH54 (2010 or 2020)");
    chain.motors.push_back({id, ping.model, ping.firmware});
    chain.fast_sync_read = chain.fast_sync_read && ping.firmware >= kFastSyncReadMinFirmware;

    write_u8(bus, id, torque_enable, 0, "torque enable");
    write_u8(bus, id, bus_watchdog, 0, "bus watchdog");
    write_u8(bus, id, return_delay_time, config.return_delay_2us, "return delay time");
    write_u8(bus, id, operating_mode, static_cast<std::uint8_t>(config.mode), "operating mode");
    write_neutral_goal(bus, id, config.mode);
    write_u8(bus, id, bus_watchdog, config.bus_watchdog_20ms, "bus watchdog");
  }
  return chain;
}

void write_baud_rate(Bus& bus, const std::vector<std::uint8_t>& ids, BaudCode code) {
  for (const std::uint8_t id : ids)
    write_u8(bus, id, baud_rate, static_cast<std::uint8_t>(code), "baud rate");
}

void set_torque(Bus& bus, const std::vector<std::uint8_t>& ids, bool enable) {
  for (const std::uint8_t id : ids)
    write_u8(bus, id, torque_enable, enable ? 1 : 0, "torque enable");
}

void hold_present_position(Bus& bus, const std::vector<std::uint8_t>& ids) {
  for (const std::uint8_t id : ids) {
    std::uint8_t position[4] = {};
    StatusError error{};
    CommResult r = CommResult::rx_timeout;
    for (int attempt = 0; attempt < kAttempts && r != CommResult::success; ++attempt)
      r = bus.read(id, present_position, position, error);
    if (r != CommResult::success || error.number() != StatusError::none)
      throw Error::at(motor_name(id), 0, "present position",
                      std::string("read failed: ") + to_string(r));
    r = CommResult::rx_timeout;
    for (int attempt = 0; attempt < kAttempts && r != CommResult::success; ++attempt)
      r = bus.write(id, goal_position, position, error);
    if (r != CommResult::success || error.number() != StatusError::none)
      throw Error::at(motor_name(id), 0, "goal position",
                      std::string("write failed: ") + to_string(r));
    write_u8(bus, id, torque_enable, 1, "torque enable");
  }
}

bool read_hardware_error(Bus& bus, std::uint8_t id, std::uint8_t& bits) noexcept {
  std::uint8_t value[1] = {};
  StatusError error{};
  if (bus.read(id, hardware_error_status, value, error) != CommResult::success) return false;
  bits = value[0];
  return true;
}

}  // namespace tpf::dxl::ph54
