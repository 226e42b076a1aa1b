// Fuzz target: parse_fast_sync_read on arbitrary responses for a fuzzer-chosen data length and
// ID list. Contract: never reads or writes out of bounds; when it accepts, the response rebuilt
// by build_fast_sync_read from the parsed fields has the same header and per-device bytes.
#include <vector>

#include "dynamixel/protocol/fast_sync_read.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tpf::dxl;
  if (size < 3) return 0;
  // Bytes 0..1: data length per device (small); byte 2: device count; then the IDs and the raw
  // response, each in its own exactly-sized buffer so ASan sees any overrun.
  const std::uint16_t length = static_cast<std::uint16_t>((data[0] | (data[1] << 8)) % 300);
  const std::size_t count = data[2] % 8;
  if (size < 3 + count) return 0;
  const std::vector<std::uint8_t> ids(data + 3, data + 3 + count);
  const std::vector<std::uint8_t> raw(data + 3 + count, data + size);
  std::vector<std::uint8_t> fields(count * length);
  std::vector<StatusError> errors(count);
  if (!parse_fast_sync_read(raw, length, ids, fields, errors)) return 0;
  std::vector<std::uint8_t> rebuilt(kMaxPacketBytes + 8 * 304);
  const std::size_t n = build_fast_sync_read(length, ids, fields, errors, rebuilt);
  if (n != raw.size()) tpf::fuzz::violation("parse_fast_sync_read", "accepted a wrong size");
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t at = kOffsetError + k * (std::size_t{length} + 4);
    if (!std::equal(raw.begin() + at, raw.begin() + at + 2 + length, rebuilt.begin() + at))
      tpf::fuzz::violation("parse_fast_sync_read", "fields differ from the response");
  }
  return 0;
}
