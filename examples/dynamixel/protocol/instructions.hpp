// Instruction packets of Protocol 2.0 (e-manual §Instruction; SDK *Tx functions).
// Each returns the packet size written to `out`, or 0 if it does not fit.
#pragma once

#include "dynamixel/protocol/packet.hpp"

namespace tpf::dxl {

/// Ping (0x01), no parameters. Status: model L, model H, firmware version.
std::size_t build_ping(std::uint8_t id, std::span<std::uint8_t> out) noexcept;

/// Read (0x02): addr L/H, len L/H.
std::size_t build_read(std::uint8_t id, std::uint16_t address, std::uint16_t length,
                       std::span<std::uint8_t> out) noexcept;

/// Write (0x03): addr L/H, data…
std::size_t build_write(std::uint8_t id, std::uint16_t address, std::span<const std::uint8_t> data,
                        std::span<std::uint8_t> out) noexcept;

/// Reboot (0x08): clears a hardware-error shutdown.
std::size_t build_reboot(std::uint8_t id, std::span<std::uint8_t> out) noexcept;

/// Sync Read (0x82) or Fast Sync Read (0x8A) to the broadcast ID: addr, len, ID1 … IDn.
std::size_t build_sync_read(Instruction inst, std::uint16_t address, std::uint16_t length,
                            std::span<const std::uint8_t> ids,
                            std::span<std::uint8_t> out) noexcept;

/// Sync Write (0x83): addr, len, then per device ID and data[len]; `data` = ids.size()·length
/// bytes in ID order.
std::size_t build_sync_write(std::uint16_t address, std::uint16_t length,
                             std::span<const std::uint8_t> ids, std::span<const std::uint8_t> data,
                             std::span<std::uint8_t> out) noexcept;

}  // namespace tpf::dxl
