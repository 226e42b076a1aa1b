// The combined Fast Sync Read (0x8A) response, sent unstuffed:
//   FF FF FD 00 FE LEN 55 | ERR1 ID1 D1[L] CRC1 | … | ERRn IDn Dn[L] CRCn,   LEN = 1 + n·(L + 4).
// CRCk is the running CRC-16 of the packet from its first FF up to block k; CRCn is the packet CRC.
#pragma once

#include "dynamixel/protocol/packet.hpp"

namespace tpf::dxl {

/// Per-device fields of a Fast Sync Read response, read as SDK GroupFastSyncRead does
/// (error at raw[8 + k·(L+4)], ID after it, data at +2). Only the final CRC is checked (by the
/// receiver). `data` gets ids.size()·length bytes, `errors` one byte per ID.
/// False if LEN does not match or a block carries an unexpected ID.
bool parse_fast_sync_read(std::span<const std::uint8_t> raw, std::uint16_t length,
                          std::span<const std::uint8_t> ids, std::span<std::uint8_t> data,
                          std::span<StatusError> errors) noexcept;

/// Device side: builds the response for `ids` from per-device `data` (ids.size()·length bytes)
/// and `errors`. Returns the packet size, or 0 if `out` is too small.
std::size_t build_fast_sync_read(std::uint16_t length, std::span<const std::uint8_t> ids,
                                 std::span<const std::uint8_t> data,
                                 std::span<const StatusError> errors,
                                 std::span<std::uint8_t> out) noexcept;

}  // namespace tpf::dxl
