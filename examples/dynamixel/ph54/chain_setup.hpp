// Start-up of a PH54 chain: identify, torque off, return delay 0, watchdog, operating mode and the
// firmware check that decides between Fast Sync Read and Sync Read. Start-up code: throws.
#pragma once

#include <cstdint>
#include <vector>

#include "dynamixel/bus/bus.hpp"
#include "dynamixel/ph54/control_table.hpp"

namespace tpf::dxl::ph54 {

struct ChainConfig {
  std::vector<std::uint8_t> ids{1, 2, 3, 4};
  std::uint8_t return_delay_2us = 0;   ///< default 250 = 500 µs per motor and Sync Read
  std::uint8_t bus_watchdog_20ms = 5;  ///< 100 ms: motors stop if the host dies; 0 disables
  OperatingMode mode = OperatingMode::current;
};

struct MotorInfo {
  std::uint8_t id = 0;
  std::uint16_t model = 0;
  std::uint8_t firmware = 0;
};

struct ChainInfo {
  std::vector<MotorInfo> motors;
  bool fast_sync_read = false;  ///< every motor has firmware ≥ 12
};

/// Pings every ID (must be a PH54: model 2010 or 2020), then writes Torque Enable = 0,
/// Bus Watchdog = 0 (clears a tripped watchdog), Return Delay Time, Operating Mode, a neutral goal
/// (current mode: Goal Current = 0; velocity mode: Goal Velocity = 0; position modes: see
/// hold_present_position) so that Torque Enable = 1 does not drive towards a stale goal, and
/// finally Bus Watchdog. Each transaction is tried up to 3 times; throws tpf::Error naming the
/// motor and register if it still fails or returns an error status.
ChainInfo set_up_chain(Bus& bus, const ChainConfig& config);

/// Writes Baud Rate(8) on every motor (torque must be off). The motors switch after the status;
/// the caller then reopens its port at baud_rate_of(code).
void write_baud_rate(Bus& bus, const std::vector<std::uint8_t>& ids, BaudCode code);

/// Torque Enable(512) on every motor.
void set_torque(Bus& bus, const std::vector<std::uint8_t>& ids, bool enable);

/// Holds the arm where it is: per motor, reads Present Position(580), writes it to Goal
/// Position(564), then Torque Enable = 1 (position mode must already be set). Writing the goal
/// first keeps the motor from jumping to a stale goal. Throws tpf::Error naming the motor.
void hold_present_position(Bus& bus, const std::vector<std::uint8_t>& ids);

/// Reads Hardware Error Status(518) of one motor (after a status with the Alert bit).
/// Returns false if the read failed. Per-cycle safe (no allocation).
bool read_hardware_error(Bus& bus, std::uint8_t id, std::uint8_t& bits) noexcept;

}  // namespace tpf::dxl::ph54
