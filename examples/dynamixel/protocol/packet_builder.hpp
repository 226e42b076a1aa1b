// Builds complete Protocol 2.0 packets (header, LEN, stuffing, CRC) into a caller's buffer.
#pragma once

#include "dynamixel/protocol/packet.hpp"

namespace tpf::dxl {

/// FF FF FD 00 | id | LEN | inst | stuffed params | CRC, with LEN = stuffed(inst+params) + 2 and
/// the CRC-16 over every byte before it. Returns the packet size, or 0 if `out` is too small.
std::size_t build_instruction(std::uint8_t id, Instruction inst,
                              std::span<const std::uint8_t> params,
                              std::span<std::uint8_t> out) noexcept;

/// Status packet FF FF FD 00 | id | LEN | 55 | err | stuffed params | CRC (device side).
std::size_t build_status(std::uint8_t id, StatusError error, std::span<const std::uint8_t> params,
                         std::span<std::uint8_t> out) noexcept;

/// Decodes a complete, CRC-checked packet from PacketReceiver. Stuffing is removed unless
/// `unstuff` is false (Fast Sync Read responses are sent unstuffed). False if malformed.
bool decode_packet(std::span<const std::uint8_t> raw, bool unstuff, Packet& out) noexcept;

}  // namespace tpf::dxl
