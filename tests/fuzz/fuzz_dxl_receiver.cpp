// Fuzz target: any byte stream from the RS-485 bus, cut into chunks of fuzzer-chosen sizes, through
// the Protocol 2.0 PacketReceiver (host or device side), then decode_packet on every packet.
// Contract: no overrun, every reported packet is a complete header-to-CRC packet of at most
// kMaxPacketBytes whose CRC matches (or is reported corrupt), and the receiver never stalls with a
// full buffer.
#include <algorithm>

#include "dynamixel/protocol/crc16.hpp"
#include "dynamixel/protocol/packet_builder.hpp"
#include "dynamixel/protocol/packet_receiver.hpp"
#include "fuzz_support.hpp"

namespace {

using tpf::fuzz::violation;
using namespace tpf::dxl;

void check_packet(std::span<const std::uint8_t> raw, bool crc_ok) {
  if (raw.size() < kHeaderBytes + 3 || raw.size() > kMaxPacketBytes)
    violation("PacketReceiver", "packet size out of range");
  if (raw[0] != 0xFF || raw[1] != 0xFF || raw[2] != 0xFD || raw[3] != 0x00)
    violation("PacketReceiver", "packet does not start with FF FF FD 00");
  const std::size_t length = raw[kOffsetLength] | (std::size_t{raw[kOffsetLength + 1]} << 8);
  if (length + kHeaderBytes != raw.size()) violation("PacketReceiver", "LEN disagrees with size");
  const std::uint16_t crc = update_crc16(0, raw.first(raw.size() - 2));
  const bool matches = crc == (raw[raw.size() - 2] | (raw[raw.size() - 1] << 8));
  if (matches != crc_ok) violation("PacketReceiver", "CRC verdict is wrong");
  Packet packet;
  for (const bool unstuff : {true, false})
    if (decode_packet(raw, unstuff, packet) && packet.param_count > kMaxParams)
      violation("decode_packet", "too many parameters");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  // Byte 0: side (bit 0) and chunk-size seed (bits 1..7).
  const auto accept =
      (data[0] & 1) ? PacketReceiver::Accept::instructions : PacketReceiver::Accept::status;
  std::size_t chunk = 1 + (data[0] >> 1);
  std::span<const std::uint8_t> stream(data + 1, size - 1);
  auto receiver = std::make_unique<PacketReceiver>(accept);
  while (!stream.empty()) {
    const std::size_t taken = receiver->feed(stream.first(std::min(chunk, stream.size())));
    stream = stream.subspan(taken);
    for (;;) {
      const RxEvent event = receiver->next();
      if (event == RxEvent::need_more) break;
      check_packet(receiver->packet(), event == RxEvent::packet);
    }
    if (taken == 0) violation("PacketReceiver", "buffer full and nothing consumed (stall)");
    chunk = chunk * 7 % 61 + 1;
  }
  // decode_packet also promises "false if malformed" on raw bytes that never met a receiver.
  Packet packet;
  static_cast<void>(decode_packet({data + 1, size - 1}, true, packet));
  static_cast<void>(decode_packet({data + 1, size - 1}, false, packet));
  return 0;
}
