// CRC-16/CCITT-FALSE: poly 0x1021, init 0xFFFF, MSB first, no reflection, no final XOR.
// Check value CRC("123456789") = 0x29B1. Firmware and host share this header.
#pragma once

#include <stddef.h>
#include <stdint.h>

namespace tpf::pad {

/// crc ← (crc << 8) ⊕ T[(crc >> 8) ⊕ b], T[i] = i·x^16 mod (x^16 + x^12 + x^5 + 1).
struct Crc16CcittTable {
  uint16_t entry[256];
  constexpr Crc16CcittTable() : entry{} {
    for (unsigned i = 0; i < 256; ++i) {
      unsigned crc = i << 8;
      for (int bit = 0; bit < 8; ++bit)
        crc = (crc & 0x8000u) ? (crc << 1) ^ 0x1021u : crc << 1;
      entry[i] = static_cast<uint16_t>(crc);
    }
  }
};

inline constexpr Crc16CcittTable kCrc16CcittTable{};

/// CRC-16/CCITT-FALSE of data[0..n), continuing from `crc` (0xFFFF for a new message).
constexpr uint16_t crc16_ccitt(const uint8_t* data, size_t n, uint16_t crc = 0xFFFF) {
  for (size_t i = 0; i < n; ++i)
    crc = static_cast<uint16_t>((crc << 8) ^ kCrc16CcittTable.entry[((crc >> 8) ^ data[i]) & 0xFF]);
  return crc;
}

}  // namespace tpf::pad
