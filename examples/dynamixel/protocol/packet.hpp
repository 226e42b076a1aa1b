// DYNAMIXEL Protocol 2.0 packet layout, instruction codes and status error byte.
//   FF FF FD 00 | ID | LEN_L LEN_H | INST | [ERR] | P1 … Pn | CRC_L CRC_H,  LEN = #after LEN.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace tpf::dxl {

inline constexpr std::uint8_t kBroadcastId = 0xFE;
inline constexpr std::size_t kHeaderBytes = 7;   ///< FF FF FD 00 ID LEN_L LEN_H
inline constexpr std::size_t kMaxLength = 1024;  ///< largest LEN accepted (SDK rxPacket)
inline constexpr std::size_t kMaxPacketBytes = kMaxLength + kHeaderBytes;
inline constexpr std::size_t kMaxParams = kMaxLength - 3;

// Byte offsets (SDK protocol2_packet_handler.cpp).
inline constexpr std::size_t kOffsetReserved = 3;
inline constexpr std::size_t kOffsetId = 4;
inline constexpr std::size_t kOffsetLength = 5;
inline constexpr std::size_t kOffsetInstruction = 7;
inline constexpr std::size_t kOffsetError = 8;

enum class Instruction : std::uint8_t {
  ping = 0x01,
  read = 0x02,
  write = 0x03,
  reboot = 0x08,
  status = 0x55,
  sync_read = 0x82,
  sync_write = 0x83,
  fast_sync_read = 0x8A,
};

/// Status ERR byte: bit 7 Alert (read Hardware Error Status 518), bits 6..0 the error number.
struct StatusError {
  std::uint8_t raw = 0;
  static constexpr std::uint8_t kAlert = 0x80;
  enum Number : std::uint8_t {
    none = 0,
    result_fail = 1,
    instruction = 2,
    crc = 3,
    data_range = 4,
    data_length = 5,
    data_limit = 6,
    access = 7
  };
  constexpr bool alert() const noexcept { return (raw & kAlert) != 0; }
  constexpr Number number() const noexcept { return static_cast<Number>(raw & 0x7F); }
};

/// A decoded packet: parameters after stuffing removal (none is removed for Fast Sync Read).
struct Packet {
  std::uint8_t id = 0;
  Instruction instruction = Instruction::ping;
  StatusError error{};  ///< status packets only
  std::uint16_t param_count = 0;
  std::array<std::uint8_t, kMaxParams> params{};

  std::span<const std::uint8_t> parameters() const noexcept { return {params.data(), param_count}; }
};

/// Little-endian helpers for control-table values.
inline void put_le(std::span<std::uint8_t> out, std::uint32_t value) noexcept {
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = static_cast<std::uint8_t>(value >> (8 * i));
}
inline std::uint32_t get_le(std::span<const std::uint8_t> in) noexcept {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < in.size() && i < 4; ++i)
    v |= std::uint32_t{in[i]} << (8 * i);
  return v;
}

}  // namespace tpf::dxl
