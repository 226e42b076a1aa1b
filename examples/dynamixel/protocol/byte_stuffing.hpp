// Protocol 2.0 byte stuffing: FF FF FD in INST/parameters is sent as FF FF FD FD.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

namespace tpf::dxl {

/// Copies `in` (INST, [ERR,] parameters) to `out`, appending FD after every FF FF FD
/// (SDK addStuffing). Returns the stuffed size, or 0 if `out` is too small.
std::size_t add_stuffing(std::span<const std::uint8_t> in, std::span<std::uint8_t> out) noexcept;

/// Copies `in` to `out`, dropping the FD of every FF FF FD FD (SDK removeStuffing).
/// `out` must hold in.size() bytes; returns the unstuffed size.
std::size_t remove_stuffing(std::span<const std::uint8_t> in, std::span<std::uint8_t> out) noexcept;

}  // namespace tpf::dxl
