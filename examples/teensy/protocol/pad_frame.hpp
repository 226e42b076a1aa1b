// Pad-board frame (hardware.md §5.1), little-endian, before COBS:
//   u8 version | u8 type | u16 seq | u32 t_us | u8 n | u8 flags | n × f32 kPa | u32 contact_mask
//   | u16 CRC-16/CCITT-FALSE over everything before it.
// On the wire: COBS(frame) followed by one 0x00. Shared by firmware and host (C++17, no heap).
#pragma once

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "cobs.hpp"
#include "crc16_ccitt.hpp"

namespace tpf::pad {

inline constexpr uint8_t kFrameVersion = 1;
inline constexpr uint8_t kTypePressureKpa = 1;  ///< n × f32 gauge pressure in kPa
inline constexpr size_t kMaxPads = 32;          ///< contact_mask has 32 bits
inline constexpr size_t kFrameOverhead = 16;    ///< header 10 + mask 4 + CRC 2
inline constexpr size_t kMaxFrameBytes = kFrameOverhead + 4 * kMaxPads;
/// Longest wire frame: COBS overhead plus the 0x00 delimiter.
inline constexpr size_t kMaxWireBytes = cobs_max_encoded_size(kMaxFrameBytes) + 1;

/// Frame flags.
enum FrameFlags : uint8_t {
  kFlagSaturated = 1 << 0,    ///< some channel hit the ADC rails
  kFlagOffsetReset = 1 << 1,  ///< zero offsets were re-captured since the previous frame
};

struct PadFrame {
  uint8_t version = kFrameVersion;
  uint8_t type = kTypePressureKpa;
  uint16_t seq = 0;   ///< +1 per frame, wraps
  uint32_t t_us = 0;  ///< device micros() at sampling, wraps every 71.6 min
  uint8_t n = 0;      ///< number of pads ≤ kMaxPads
  uint8_t flags = 0;
  float kpa[kMaxPads] = {};
  uint32_t contact_mask = 0;  ///< bit k: pad k+1 in contact
};

enum class FrameError : uint8_t { none, length, crc, version, type, count };

namespace detail {
inline void put_u16(uint8_t* p, uint16_t v) {
  p[0] = uint8_t(v);
  p[1] = uint8_t(v >> 8);
}
inline void put_u32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i)
    p[i] = uint8_t(v >> (8 * i));
}
inline uint16_t get_u16(const uint8_t* p) {
  return uint16_t(p[0] | (p[1] << 8));
}
inline uint32_t get_u32(const uint8_t* p) {
  return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}
}  // namespace detail

/// Serialises `f` (n clamped to kMaxPads) with its CRC into raw[kMaxFrameBytes]; returns the size.
inline size_t serialize_frame(const PadFrame& f, uint8_t* raw) {
  const size_t n = f.n < kMaxPads ? f.n : kMaxPads;
  raw[0] = f.version;
  raw[1] = f.type;
  detail::put_u16(raw + 2, f.seq);
  detail::put_u32(raw + 4, f.t_us);
  raw[8] = uint8_t(n);
  raw[9] = f.flags;
  for (size_t k = 0; k < n; ++k) {
    uint32_t bits;
    memcpy(&bits, &f.kpa[k], 4);
    detail::put_u32(raw + 10 + 4 * k, bits);
  }
  detail::put_u32(raw + 10 + 4 * n, f.contact_mask);
  const size_t crc_at = 14 + 4 * n;
  detail::put_u16(raw + crc_at, crc16_ccitt(raw, crc_at));
  return crc_at + 2;
}

/// Wire bytes for `f`: COBS(frame) 00. `wire` has room for kMaxWireBytes; returns the size.
inline size_t encode_frame(const PadFrame& f, uint8_t* wire) {
  uint8_t raw[kMaxFrameBytes];
  const size_t n = cobs_encode(raw, serialize_frame(f, raw), wire);
  wire[n] = 0x00;
  return n + 1;
}

/// Parses a COBS-decoded frame, checking CRC, version, type and that the size matches n.
inline FrameError parse_frame(const uint8_t* raw, size_t size, PadFrame& f) {
  if (size < kFrameOverhead) return FrameError::length;
  if (crc16_ccitt(raw, size - 2) != detail::get_u16(raw + size - 2)) return FrameError::crc;
  if (raw[0] != kFrameVersion) return FrameError::version;
  if (raw[1] != kTypePressureKpa) return FrameError::type;
  const size_t n = raw[8];
  if (n > kMaxPads || size != kFrameOverhead + 4 * n) return FrameError::count;
  f.version = raw[0];
  f.type = raw[1];
  f.seq = detail::get_u16(raw + 2);
  f.t_us = detail::get_u32(raw + 4);
  f.n = uint8_t(n);
  f.flags = raw[9];
  for (size_t k = 0; k < n; ++k) {
    const uint32_t bits = detail::get_u32(raw + 10 + 4 * k);
    memcpy(&f.kpa[k], &bits, 4);
  }
  f.contact_mask = detail::get_u32(raw + 10 + 4 * n);
  return FrameError::none;
}

}  // namespace tpf::pad
