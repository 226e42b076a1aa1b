#include "dynamixel/protocol/packet_builder.hpp"

#include <algorithm>

#include "dynamixel/protocol/byte_stuffing.hpp"
#include "dynamixel/protocol/crc16.hpp"

namespace tpf::dxl {
namespace {

/// Header, stuffed body (INST [ERR] params), LEN and CRC.
std::size_t build_packet(std::uint8_t id, std::span<const std::uint8_t> body,
                         std::span<std::uint8_t> out) noexcept {
  if (out.size() < kHeaderBytes + 2) return 0;
  const std::size_t stuffed =
      add_stuffing(body, out.subspan(kHeaderBytes, out.size() - kHeaderBytes - 2));
  if (stuffed == 0 || stuffed + 2 > kMaxLength) return 0;
  const std::size_t length = stuffed + 2;
  out[0] = 0xFF;
  out[1] = 0xFF;
  out[2] = 0xFD;
  out[3] = 0x00;
  out[4] = id;
  out[5] = static_cast<std::uint8_t>(length & 0xFF);
  out[6] = static_cast<std::uint8_t>(length >> 8);
  const std::size_t crc_at = kHeaderBytes + stuffed;
  const std::uint16_t crc = update_crc16(0, out.first(crc_at));
  out[crc_at] = static_cast<std::uint8_t>(crc & 0xFF);
  out[crc_at + 1] = static_cast<std::uint8_t>(crc >> 8);
  return crc_at + 2;
}

}  // namespace

std::size_t build_instruction(std::uint8_t id, Instruction inst,
                              std::span<const std::uint8_t> params,
                              std::span<std::uint8_t> out) noexcept {
  std::array<std::uint8_t, kMaxParams + 1> body;
  if (params.size() > kMaxParams) return 0;
  body[0] = static_cast<std::uint8_t>(inst);
  std::copy(params.begin(), params.end(), body.begin() + 1);
  return build_packet(id, std::span(body).first(params.size() + 1), out);
}

std::size_t build_status(std::uint8_t id, StatusError error, std::span<const std::uint8_t> params,
                         std::span<std::uint8_t> out) noexcept {
  std::array<std::uint8_t, kMaxParams + 1> body;
  if (params.size() + 1 > kMaxParams) return 0;
  body[0] = static_cast<std::uint8_t>(Instruction::status);
  body[1] = error.raw;
  std::copy(params.begin(), params.end(), body.begin() + 2);
  return build_packet(id, std::span(body).first(params.size() + 2), out);
}

bool decode_packet(std::span<const std::uint8_t> raw, bool unstuff, Packet& out) noexcept {
  if (raw.size() < kHeaderBytes + 3) return false;
  const std::size_t length = raw[kOffsetLength] | (std::size_t{raw[kOffsetLength + 1]} << 8);
  if (raw.size() != length + kHeaderBytes || length < 3 || length > kMaxLength) return false;
  std::array<std::uint8_t, kMaxLength> body;
  const auto stuffed = raw.subspan(kOffsetInstruction, length - 2);
  const std::size_t n =
      unstuff ? remove_stuffing(stuffed, body)
              : (std::copy(stuffed.begin(), stuffed.end(), body.begin()), stuffed.size());
  out.id = raw[kOffsetId];
  out.instruction = static_cast<Instruction>(body[0]);
  std::size_t first_param = 1;
  out.error = StatusError{};
  if (out.instruction == Instruction::status) {
    if (n < 2) return false;
    out.error = StatusError{body[1]};
    first_param = 2;
  }
  out.param_count = static_cast<std::uint16_t>(n - first_param);
  std::copy_n(body.begin() + static_cast<std::ptrdiff_t>(first_param), out.param_count,
              out.params.begin());
  return true;
}

}  // namespace tpf::dxl
