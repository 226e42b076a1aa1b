// CRC-16 of DYNAMIXEL Protocol 2.0: CRC-16/UMTS (alias BUYPASS), poly 0x8005, init 0, MSB first,
// no reflection, no final XOR. Check value CRC("123456789") = 0xFEE8.
#pragma once

#include <array>
#include <cstdint>
#include <span>

namespace tpf::dxl {

/// T[i] = the CRC register after shifting byte i through 8 MSB-first steps of poly 0x8005.
constexpr std::array<std::uint16_t, 256> make_crc16_table() noexcept {
  std::array<std::uint16_t, 256> table{};
  for (unsigned i = 0; i < 256; ++i) {
    unsigned crc = i << 8;
    for (int bit = 0; bit < 8; ++bit)
      crc = (crc & 0x8000u) ? (crc << 1) ^ 0x8005u : crc << 1;
    table[i] = static_cast<std::uint16_t>(crc);
  }
  return table;
}

inline constexpr std::array<std::uint16_t, 256> kCrc16Table = make_crc16_table();

/// Table-driven update as SDK updateCRC: crc ← (crc << 8) ⊕ T[((crc >> 8) ⊕ b) & 0xFF] per byte.
/// Start from crc = 0 at the first 0xFF of the header; chaining calls continues the same CRC.
constexpr std::uint16_t update_crc16(std::uint16_t crc,
                                     std::span<const std::uint8_t> data) noexcept {
  for (const std::uint8_t b : data)
    crc = static_cast<std::uint16_t>((crc << 8) ^ kCrc16Table[((crc >> 8) ^ b) & 0xFFu]);
  return crc;
}

}  // namespace tpf::dxl
