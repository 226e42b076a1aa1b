// Inputs from the bus and the pad board that the fuzzers (tests/fuzz) crashed on or that probe
// the same edges: each is a fixed regression test here, and stays in the fuzz seed corpus.
#include <gtest/gtest.h>

#include <vector>

#include "dynamixel/protocol/packet_builder.hpp"
#include "dynamixel/protocol/packet_receiver.hpp"

namespace tpf::dxl {
namespace {

/// FF FF FD 00 | id | LEN | 55 | payload…: a status-shaped packet of `length` (no valid CRC).
std::vector<std::uint8_t> raw_packet(std::size_t length) {
  std::vector<std::uint8_t> raw(length + kHeaderBytes, 0x11);
  const std::uint8_t header[] = {0xFF,
                                 0xFF,
                                 0xFD,
                                 0x00,
                                 0x01,
                                 static_cast<std::uint8_t>(length & 0xFF),
                                 static_cast<std::uint8_t>(length >> 8),
                                 0x55};
  for (std::size_t i = 0; i < sizeof header; ++i)
    raw[i] = header[i];
  return raw;
}

// fuzz_dxl_receiver, crash-decode-len-over-max: LEN = 1093 made decode_packet unstuff 1091 bytes
// into its 1024-byte stack buffer (stack-buffer-overflow). It must refuse LEN > kMaxLength.
TEST(DeviceFuzzRegressions, DecodePacketRefusesLengthAboveTheProtocolMaximum) {
  Packet packet;
  for (const std::size_t length : {kMaxLength + 1, std::size_t{1093}, std::size_t{0xFFFF}}) {
    const auto raw = raw_packet(length);
    EXPECT_FALSE(decode_packet(raw, true, packet)) << length;
    EXPECT_FALSE(decode_packet(raw, false, packet)) << length;
  }
  // The largest legal status packet still decodes: LEN 1024 = INST + ERR + 1020 parameters + CRC.
  const auto largest = raw_packet(kMaxLength);
  ASSERT_TRUE(decode_packet(largest, false, packet));
  EXPECT_EQ(packet.param_count, kMaxLength - 4);
}

// The receiver never hands such a packet on: it drops the header and resynchronises on the
// valid packet behind it.
TEST(DeviceFuzzRegressions, ReceiverSkipsAnOverlongHeaderAndFindsTheNextPacket) {
  std::vector<std::uint8_t> stream = raw_packet(1093);
  stream.resize(40);  // only the start of the bogus packet arrives
  std::array<std::uint8_t, 32> good{};
  const std::uint8_t params[] = {0x0E, 0x08, 0x2D};
  const std::size_t n = build_status(7, StatusError{}, params, good);
  stream.insert(stream.end(), good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
  PacketReceiver receiver(PacketReceiver::Accept::status);
  ASSERT_EQ(receiver.feed(stream), stream.size());
  ASSERT_EQ(receiver.next(), RxEvent::packet);
  Packet packet;
  ASSERT_TRUE(decode_packet(receiver.packet(), true, packet));
  EXPECT_EQ(packet.id, 7);
  EXPECT_EQ(packet.param_count, 3);
  EXPECT_EQ(receiver.dropped_bytes(), 40u);
}

}  // namespace
}  // namespace tpf::dxl
