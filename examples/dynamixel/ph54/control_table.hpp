// DYNAMIXEL-P PH54-200-S500-R / PH54-100-S500-R control table (e-manual; hardware.md §2.2–2.4).
#pragma once

#include <cstdint>

namespace tpf::dxl::ph54 {

/// Control-table addresses. EEPROM (< 512) is writable only with torque off.
enum Address : std::uint16_t {
  model_number = 0,             ///< 2 B: 2020 (PH54-200), 2010 (PH54-100)
  firmware_version = 6,         ///< 1 B: Fast Sync Read needs ≥ 12
  id = 7,                       ///< 1 B
  baud_rate = 8,                ///< 1 B: BaudCode
  return_delay_time = 9,        ///< 1 B: × 2 µs, default 250 (500 µs)
  operating_mode = 11,          ///< 1 B: OperatingMode
  homing_offset = 20,           ///< 4 B: pulse
  current_limit = 38,           ///< 2 B: mA
  velocity_limit = 44,          ///< 4 B: 0.01 rev/min
  max_position_limit = 48,      ///< 4 B: pulse
  min_position_limit = 52,      ///< 4 B: pulse
  shutdown = 63,                ///< 1 B: HardwareError bit mask
  torque_enable = 512,          ///< 1 B
  hardware_error_status = 518,  ///< 1 B: HardwareError bits
  bus_watchdog = 546,           ///< 1 B: × 20 ms, 0 disables, 0xFF (−1) = watchdog tripped
  goal_current = 550,           ///< 2 B: mA, signed
  goal_velocity = 552,          ///< 4 B: 0.01 rev/min, signed
  goal_position = 564,          ///< 4 B: pulse, signed
  realtime_tick = 568,          ///< 2 B: ms, 0…32767
  present_current = 574,        ///< 2 B: mA, signed
  present_velocity = 576,       ///< 4 B: 0.01 rev/min, signed
  present_position = 580,       ///< 4 B: pulse, signed
  present_input_voltage = 592,  ///< 2 B: 0.1 V
  present_temperature = 594,    ///< 1 B: °C
};

/// Present Current, Velocity and Position are one contiguous block: one (Fast) Sync Read.
inline constexpr std::uint16_t kStateAddress = present_current;
inline constexpr std::uint16_t kStateLength = 10;

inline constexpr std::uint16_t kModelPh54_200 = 2020;
inline constexpr std::uint16_t kModelPh54_100 = 2010;
inline constexpr std::uint8_t kFastSyncReadMinFirmware = 12;
inline constexpr std::uint16_t kEepromEnd = 512;  ///< addresses below are EEPROM

enum class OperatingMode : std::uint8_t {
  current = 0,
  velocity = 1,
  position = 3,
  extended_position = 4,
  pwm = 16
};

/// Baud Rate(8) codes; 6 = 4 Mbps is exact on PH54 and U2D2.
enum class BaudCode : std::uint8_t {
  b9600 = 0,
  b57600 = 1,
  b115200 = 2,
  b1M = 3,
  b2M = 4,
  b3M = 5,
  b4M = 6,
  b4_5M = 7,
  b6M = 8,
  b10_5M = 9
};

/// Baud code → bit/s (4.5 M is nominal); 0 for an unknown code.
constexpr int baud_rate_of(BaudCode code) noexcept {
  constexpr int rates[] = {9600,      57600,     115200,    1'000'000, 2'000'000,
                           3'000'000, 4'000'000, 4'500'000, 6'000'000, 10'500'000};
  const auto i = static_cast<unsigned>(code);
  return i < 10 ? rates[i] : 0;
}

/// Hardware Error Status(518) / Shutdown(63) bits.
enum HardwareError : std::uint8_t {
  input_voltage = 1 << 0,
  motor_hall_sensor = 1 << 1,
  overheating = 1 << 2,
  motor_encoder = 1 << 3,
  electrical_shock = 1 << 4,
  overload = 1 << 5,
};

}  // namespace tpf::dxl::ph54
