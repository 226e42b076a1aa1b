// Consistent Overhead Byte Stuffing (Cheshire & Baker, 1999). The encoded bytes contain no 0x00,
// so 0x00 delimits frames. Shared by the Teensy firmware (C++17, no std library containers) and
// the host.
#pragma once

#include <stddef.h>
#include <stdint.h>

namespace tpf::pad {

/// Largest encoding of n bytes: n + ⌈n/254⌉ + 1 (without the delimiter).
constexpr size_t cobs_max_encoded_size(size_t n) {
  return n + n / 254 + 1;
}

/// Encodes `in[0..n)` into `out` (room for cobs_max_encoded_size(n)); returns the encoded size.
/// Each block is a code byte c followed by c − 1 non-zero bytes; c < 0xFF implies a zero after it.
inline size_t cobs_encode(const uint8_t* in, size_t n, uint8_t* out) {
  size_t code_at = 0;  // where the current block's code byte goes
  size_t o = 1;
  uint8_t code = 1;
  for (size_t i = 0; i < n; ++i) {
    if (in[i] != 0) {
      out[o++] = in[i];
      ++code;
    }
    if (in[i] == 0 || code == 0xFF) {
      out[code_at] = code;
      code = 1;
      code_at = o;
      // A full block at the very end needs no trailing code byte.
      if (in[i] == 0 || i + 1 < n) ++o;
    }
  }
  if (code_at < o) out[code_at] = code;
  return o;
}

/// Decodes `in[0..n)` (one frame, delimiter removed) into `out` (room for n bytes).
/// Returns false if a code byte is 0 or points past the end of the frame.
inline bool cobs_decode(const uint8_t* in, size_t n, uint8_t* out, size_t* out_size) {
  size_t i = 0;
  size_t o = 0;
  while (i < n) {
    const uint8_t code = in[i++];
    if (code == 0 || i + code - 1 > n) return false;
    for (uint8_t k = 1; k < code; ++k) {
      if (in[i] == 0) return false;
      out[o++] = in[i++];
    }
    if (code != 0xFF && i < n) out[o++] = 0;
  }
  *out_size = o;
  return true;
}

}  // namespace tpf::pad
