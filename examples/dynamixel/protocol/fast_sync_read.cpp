#include "dynamixel/protocol/fast_sync_read.hpp"

#include <algorithm>

#include "dynamixel/protocol/crc16.hpp"

namespace tpf::dxl {

bool parse_fast_sync_read(std::span<const std::uint8_t> raw, std::uint16_t length,
                          std::span<const std::uint8_t> ids, std::span<std::uint8_t> data,
                          std::span<StatusError> errors) noexcept {
  const std::size_t block = std::size_t{length} + 4;
  const std::size_t expected = 1 + ids.size() * block;
  if (raw.size() != expected + kHeaderBytes || raw[kOffsetId] != kBroadcastId) return false;
  if ((raw[kOffsetLength] | (std::size_t{raw[kOffsetLength + 1]} << 8)) != expected) return false;
  if (data.size() < ids.size() * length || errors.size() < ids.size()) return false;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::size_t at = kOffsetError + k * block;
    if (raw[at + 1] != ids[k]) return false;
    errors[k] = StatusError{raw[at]};
    std::copy_n(raw.begin() + static_cast<std::ptrdiff_t>(at + 2), length,
                data.begin() + static_cast<std::ptrdiff_t>(k * length));
  }
  return true;
}

std::size_t build_fast_sync_read(std::uint16_t length, std::span<const std::uint8_t> ids,
                                 std::span<const std::uint8_t> data,
                                 std::span<const StatusError> errors,
                                 std::span<std::uint8_t> out) noexcept {
  const std::size_t block = std::size_t{length} + 4;
  const std::size_t len_field = 1 + ids.size() * block;
  if (len_field > kMaxLength || out.size() < len_field + kHeaderBytes ||
      data.size() != ids.size() * length || errors.size() != ids.size())
    return 0;
  const std::uint8_t header[] = {0xFF,
                                 0xFF,
                                 0xFD,
                                 0x00,
                                 kBroadcastId,
                                 static_cast<std::uint8_t>(len_field & 0xFF),
                                 static_cast<std::uint8_t>(len_field >> 8),
                                 static_cast<std::uint8_t>(Instruction::status)};
  std::copy(std::begin(header), std::end(header), out.begin());
  std::size_t n = sizeof header;
  std::uint16_t crc = update_crc16(0, std::span<const std::uint8_t>(header));
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const std::size_t start = n;
    out[n++] = errors[k].raw;
    out[n++] = ids[k];
    std::copy_n(data.begin() + static_cast<std::ptrdiff_t>(k * length), length,
                out.begin() + static_cast<std::ptrdiff_t>(n));
    n += length;
    crc = update_crc16(crc, out.subspan(start, n - start));  // running CRC up to this block
    out[n++] = static_cast<std::uint8_t>(crc & 0xFF);
    out[n++] = static_cast<std::uint8_t>(crc >> 8);
    crc = update_crc16(crc, out.subspan(n - 2, 2));
  }
  return n;
}

}  // namespace tpf::dxl
