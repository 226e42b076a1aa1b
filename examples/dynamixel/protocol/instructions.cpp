#include "dynamixel/protocol/instructions.hpp"

#include <algorithm>

#include "dynamixel/protocol/packet_builder.hpp"

namespace tpf::dxl {
namespace {

/// Parameter buffer starting with a little-endian address (and optionally a length).
struct Params {
  std::array<std::uint8_t, kMaxParams> bytes;
  std::size_t size = 0;

  void u8(std::uint8_t v) noexcept {
    if (size < bytes.size()) bytes[size++] = v;
  }
  void u16(std::uint16_t v) noexcept {
    u8(static_cast<std::uint8_t>(v & 0xFF));
    u8(static_cast<std::uint8_t>(v >> 8));
  }
  bool fits(std::size_t more) const noexcept { return size + more <= bytes.size(); }
  std::span<const std::uint8_t> view() const noexcept { return {bytes.data(), size}; }
};

}  // namespace

std::size_t build_ping(std::uint8_t id, std::span<std::uint8_t> out) noexcept {
  return build_instruction(id, Instruction::ping, {}, out);
}

std::size_t build_read(std::uint8_t id, std::uint16_t address, std::uint16_t length,
                       std::span<std::uint8_t> out) noexcept {
  Params p;
  p.u16(address);
  p.u16(length);
  return build_instruction(id, Instruction::read, p.view(), out);
}

std::size_t build_write(std::uint8_t id, std::uint16_t address, std::span<const std::uint8_t> data,
                        std::span<std::uint8_t> out) noexcept {
  Params p;
  p.u16(address);
  if (!p.fits(data.size())) return 0;
  for (const std::uint8_t b : data)
    p.u8(b);
  return build_instruction(id, Instruction::write, p.view(), out);
}

std::size_t build_reboot(std::uint8_t id, std::span<std::uint8_t> out) noexcept {
  return build_instruction(id, Instruction::reboot, {}, out);
}

std::size_t build_sync_read(Instruction inst, std::uint16_t address, std::uint16_t length,
                            std::span<const std::uint8_t> ids,
                            std::span<std::uint8_t> out) noexcept {
  Params p;
  p.u16(address);
  p.u16(length);
  if (!p.fits(ids.size())) return 0;
  for (const std::uint8_t id : ids)
    p.u8(id);
  return build_instruction(kBroadcastId, inst, p.view(), out);
}

std::size_t build_sync_write(std::uint16_t address, std::uint16_t length,
                             std::span<const std::uint8_t> ids, std::span<const std::uint8_t> data,
                             std::span<std::uint8_t> out) noexcept {
  if (data.size() != ids.size() * length) return 0;
  Params p;
  p.u16(address);
  p.u16(length);
  if (!p.fits(ids.size() * (1 + length))) return 0;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    p.u8(ids[k]);
    for (std::size_t j = 0; j < length; ++j)
      p.u8(data[k * length + j]);
  }
  return build_instruction(kBroadcastId, Instruction::sync_write, p.view(), out);
}

}  // namespace tpf::dxl
