// Per-cycle read of a PH54 chain: Present Current, Velocity and Position (574, 10 bytes) of every
// motor in one Fast Sync Read, or one Sync Read on firmware < 12. No allocation.
#pragma once

#include <array>
#include <cstdint>

#include "dynamixel/bus/bus.hpp"

namespace tpf::dxl::ph54 {

inline constexpr std::size_t kMaxChainMotors = 16;

/// One motor's state in SI units, output side.
struct JointReading {
  double position_rad = 0.0;    ///< pulse · 2π/1,003,846
  double velocity_rad_s = 0.0;  ///< 0.01 rev/min units
  double current_mA = 0.0;      ///< signed mA as the drive reports it
  StatusError error{};          ///< ERR byte of this motor's status (Alert = bit 7)
};

class ChainStateReader {
 public:
  /// `ids` at most kMaxChainMotors; `fast` from ChainInfo::fast_sync_read.
  ChainStateReader(Bus& bus, std::span<const std::uint8_t> ids, bool fast) noexcept;

  /// One transaction; fills out[0..ids.size()) on success.
  CommResult read(std::span<JointReading> out) noexcept;

  std::size_t size() const noexcept { return count_; }
  bool fast() const noexcept { return fast_; }

 private:
  Bus& bus_;
  std::array<std::uint8_t, kMaxChainMotors> ids_{};
  std::size_t count_ = 0;
  bool fast_ = false;
  std::array<std::uint8_t, kMaxChainMotors * 10> data_{};
  std::array<StatusError, kMaxChainMotors> errors_{};
};

}  // namespace tpf::dxl::ph54
