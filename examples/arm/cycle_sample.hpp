// Everything the 400 Hz loop measured in one cycle: the input of the estimator and one log row.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace tpf::arm {

inline constexpr std::size_t kMaxJoints = 8;
inline constexpr std::size_t kMaxPads = 32;

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
};

}  // namespace tpf::arm
