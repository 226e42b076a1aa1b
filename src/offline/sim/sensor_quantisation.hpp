// How the PH54 reports its state (hardware.md §2): position in pulses of 2π/1,003,846 rad,
// velocity in steps of 0.01 rev/min, current in steps of 1 mA.
#pragma once

#include <cmath>
#include <numbers>

namespace tpf::offline {

inline constexpr double kPh54PulsesPerRev = 1003846.0;
inline constexpr double kPositionStep = 2.0 * std::numbers::pi / kPh54PulsesPerRev;  ///< rad
inline constexpr double kVelocityStep = 2.0 * std::numbers::pi / 6000.0;  ///< 0.01 rpm in rad/s

/// Position as the encoder reports it: round(q/step)·step.
inline double quantise_position(double q) {
  return std::round(q / kPositionStep) * kPositionStep;
}
/// Velocity as the drive reports it: round(q̇/step)·step.
inline double quantise_velocity(double dq) {
  return std::round(dq / kVelocityStep) * kVelocityStep;
}
/// Current in whole mA.
inline double quantise_current_ma(double milliamps) {
  return std::round(milliamps);
}

}  // namespace tpf::offline
