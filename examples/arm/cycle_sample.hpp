// Everything the 400 Hz loop measured in one cycle, and what the estimator made of it: one log
// row.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace tpf::arm {

inline constexpr std::size_t kMaxJoints = 8;
inline constexpr std::size_t kMaxPads = 32;

/// The estimator's answer for one cycle (ArmLoop copies it from the EstimatorHook).
struct CycleEstimate {
  bool present = false;      ///< false: no estimator, or it skipped the cycle (NaN in the log)
  std::uint32_t status = 0;  ///< EstimatorStatus bits
  bool contact = false;      ///< contact believed (a pad, or the torque alarm)
  int contact_pad = -1;      ///< most loaded pad in contact (0-based), −1: none
  std::array<double, kMaxJoints> external_torque_nm{};  ///< τ̂_ext [N·m]
  std::array<double, 3> force_world_n{};                ///< contact force at contact_pad, world [N]
};

struct CycleSample {
  std::uint64_t cycle = 0;
  double t = 0.0;  ///< s since the loop started (CLOCK_MONOTONIC at the bus read)
  std::size_t joints = 0;
  bool motors_valid = false;  ///< false: the motor read failed this cycle (values are stale)
  std::array<double, kMaxJoints> q{};   ///< rad, output side
  std::array<double, kMaxJoints> dq{};  ///< rad/s
  std::array<double, kMaxJoints> i{};   ///< mA as the drive reports it
  std::size_t pads = 0;
  bool pads_valid = false;          ///< false: no pad frame within the staleness bound
  double pad_age_s = 0.0;           ///< cycle time − device sampling time of the pad frame
  std::array<float, kMaxPads> p{};  ///< kPa gauge
  std::uint32_t contact_mask = 0;
  CycleEstimate estimate;
};

}  // namespace tpf::arm
