// PH54 register units ↔ SI (hardware.md §2.5). Output side of the 501.923:1 gear.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace tpf::dxl::ph54 {

inline constexpr double kPulsePerRev = 1'003'846.0;  ///< PH54 (the old non-P H54: 501,923)
inline constexpr double kRadPerPulse = 2.0 * std::numbers::pi / kPulsePerRev;      ///< 6.259113e-6
inline constexpr double kRadPerSecPerUnit = 0.01 * 2.0 * std::numbers::pi / 60.0;  ///< 0.01 rpm
inline constexpr double kAmperePerUnit = 1e-3;                                     ///< 1 mA
inline constexpr double kVoltPerUnit = 0.1;                                        ///< 0.1 V

/// rad = pulse · 2π / 1,003,846.
constexpr double position_to_rad(std::int32_t pulse) noexcept {
  return pulse * kRadPerPulse;
}
/// pulse = round(rad / (2π / 1,003,846)).
inline std::int32_t rad_to_position(double rad) noexcept {
  return static_cast<std::int32_t>(std::lround(rad / kRadPerPulse));
}
/// rad/s = value · 0.01 rev/min · 2π / 60.
constexpr double velocity_to_rad_s(std::int32_t value) noexcept {
  return value * kRadPerSecPerUnit;
}
inline std::int32_t rad_s_to_velocity(double rad_s) noexcept {
  return static_cast<std::int32_t>(std::lround(rad_s / kRadPerSecPerUnit));
}
/// Present/Goal Current are signed mA; the log keeps mA (log-format.md: column i<j>).
constexpr double current_to_ampere(std::int16_t milliampere) noexcept {
  return milliampere * kAmperePerUnit;
}
inline std::int16_t ampere_to_current(double ampere) noexcept {
  return static_cast<std::int16_t>(
      std::lround(std::clamp(ampere / kAmperePerUnit, -32768.0, 32767.0)));
}
/// V = value · 0.1.
constexpr double voltage_to_volt(std::uint16_t value) noexcept {
  return value * kVoltPerUnit;
}

}  // namespace tpf::dxl::ph54
