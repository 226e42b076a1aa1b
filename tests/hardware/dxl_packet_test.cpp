// Every Protocol 2.0 vector of hardware.md §1.6: build → exact bytes, parse → exact values.
#include <gtest/gtest.h>

#include <array>

#include "dynamixel/protocol/crc16.hpp"
#include "dynamixel/protocol/instructions.hpp"
#include "dynamixel/protocol/packet_builder.hpp"
#include "dynamixel/protocol/packet_receiver.hpp"
#include "hex.hpp"

namespace tpf::dxl {
namespace {

using test::hex;
using test::to_hex;

std::string built(std::size_t n, const std::array<std::uint8_t, kMaxPacketBytes>& out) {
  return to_hex(std::span(out).first(n));
}

/// Feeds raw bytes and expects exactly one CRC-valid packet.
Packet receive_one(const std::vector<std::uint8_t>& raw, PacketReceiver::Accept accept,
                   bool unstuff = true) {
  PacketReceiver rx(accept);
  EXPECT_EQ(rx.feed(raw), raw.size());
  Packet p;
  EXPECT_EQ(rx.next(), RxEvent::packet);
  EXPECT_TRUE(decode_packet(rx.packet(), unstuff, p));
  EXPECT_EQ(rx.next(), RxEvent::need_more);
  return p;
}

TEST(DxlCrc16, CheckValueAndTable) {
  const std::string_view text = "123456789";
  const std::span bytes(reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
  EXPECT_EQ(update_crc16(0, bytes), 0xFEE8);
  const std::uint16_t head[] = {0x0000, 0x8005, 0x800F, 0x000A, 0x801B,
                                0x001E, 0x0014, 0x8011, 0x8033, 0x0036};
  for (std::size_t i = 0; i < std::size(head); ++i)
    EXPECT_EQ(kCrc16Table[i], head[i]) << i;
  EXPECT_EQ(kCrc16Table[255], 0x0202);
  // Chaining equals one pass.
  EXPECT_EQ(update_crc16(update_crc16(0, bytes.first(4)), bytes.subspan(4)), 0xFEE8);
}

TEST(DxlBuild, EmanualVectors) {
  std::array<std::uint8_t, kMaxPacketBytes> out{};
  EXPECT_EQ(built(build_ping(1, out), out), "FF FF FD 00 01 03 00 01 19 4E");
  EXPECT_EQ(built(build_ping(kBroadcastId, out), out), "FF FF FD 00 FE 03 00 01 31 42");
  EXPECT_EQ(built(build_read(1, 132, 4, out), out), "FF FF FD 00 01 07 00 02 84 00 04 00 1D 15");
  const std::uint8_t v512[] = {0x00, 0x02, 0x00, 0x00};
  EXPECT_EQ(built(build_write(1, 116, v512, out), out),
            "FF FF FD 00 01 09 00 03 74 00 00 02 00 00 CA 89");
  const std::uint8_t ids12[] = {1, 2};
  EXPECT_EQ(built(build_sync_read(Instruction::sync_read, 132, 4, ids12, out), out),
            "FF FF FD 00 FE 09 00 82 84 00 04 00 01 02 CE FA");
  const std::uint8_t sw[] = {0x96, 0, 0, 0, 0xAA, 0, 0, 0};
  EXPECT_EQ(built(build_sync_write(116, 4, ids12, sw, out), out),
            "FF FF FD 00 FE 11 00 83 74 00 04 00 01 96 00 00 00 02 AA 00 00 00 82 87");
  const std::uint8_t ids374[] = {3, 7, 4};
  EXPECT_EQ(built(build_sync_read(Instruction::fast_sync_read, 132, 4, ids374, out), out),
            "FF FF FD 00 FE 0A 00 8A 84 00 04 00 03 07 04 20 F2");
  EXPECT_EQ(built(build_sync_read(Instruction::fast_sync_read, 580, 4, ids12, out), out),
            "FF FF FD 00 FE 09 00 8A 44 02 04 00 01 02 72 F2");
  // Bulk Read is not used by the adapters; its vector still checks LEN and CRC of a raw build.
  const std::uint8_t bulk[] = {0x01, 0x90, 0x00, 0x02, 0x00, 0x02, 0x92, 0x00, 0x01, 0x00};
  EXPECT_EQ(built(build_instruction(kBroadcastId, static_cast<Instruction>(0x92), bulk, out), out),
            "FF FF FD 00 FE 0D 00 92 01 90 00 02 00 02 92 00 01 00 1A 05");
}

TEST(DxlBuild, StatusVectors) {
  std::array<std::uint8_t, kMaxPacketBytes> out{};
  const std::uint8_t ping[] = {0x06, 0x04, 0x26};
  EXPECT_EQ(built(build_status(1, {}, ping, out), out),
            "FF FF FD 00 01 07 00 55 00 06 04 26 65 5D");
  const std::uint8_t read[] = {0xA6, 0, 0, 0};
  EXPECT_EQ(built(build_status(1, {}, read, out), out),
            "FF FF FD 00 01 08 00 55 00 A6 00 00 00 8C C0");
  EXPECT_EQ(built(build_status(1, {}, {}, out), out), "FF FF FD 00 01 04 00 55 00 A1 0C");
  std::array<std::uint8_t, 10> state{};
  put_le(std::span(state).subspan(0, 2), static_cast<std::uint16_t>(-150));
  put_le(std::span(state).subspan(2, 4), 1234);
  put_le(std::span(state).subspan(6, 4), 250961);
  EXPECT_EQ(built(build_status(1, {}, state, out), out),
            "FF FF FD 00 01 0E 00 55 00 6A FF D2 04 00 00 51 D4 03 00 43 63");
  const std::uint8_t stuffed[] = {0xFF, 0xFF, 0xFD, 0xFF};
  EXPECT_EQ(built(build_status(1, {}, stuffed, out), out),
            "FF FF FD 00 01 09 00 55 00 FF FF FD FD FF DA 9E");
}

TEST(DxlBuild, Ph54Vectors) {
  std::array<std::uint8_t, kMaxPacketBytes> out{};
  const std::uint8_t one[] = {1};
  EXPECT_EQ(built(build_write(1, 512, one, out), out), "FF FF FD 00 01 06 00 03 00 02 01 DB 6F");
  EXPECT_EQ(built(build_read(1, 580, 4, out), out), "FF FF FD 00 01 07 00 02 44 02 04 00 14 95");
  const std::uint8_t ids[] = {1, 2, 3, 4};
  EXPECT_EQ(built(build_sync_read(Instruction::sync_read, 574, 10, ids, out), out),
            "FF FF FD 00 FE 0B 00 82 3E 02 0A 00 01 02 03 04 BA 4F");
  EXPECT_EQ(built(build_sync_read(Instruction::fast_sync_read, 574, 10, ids, out), out),
            "FF FF FD 00 FE 0B 00 8A 3E 02 0A 00 01 02 03 04 B9 FC");
  std::array<std::uint8_t, 8> goal{};
  const std::int16_t mA[] = {100, -200, 300, -400};
  for (int k = 0; k < 4; ++k)
    put_le(std::span(goal).subspan(2 * k, 2), static_cast<std::uint16_t>(mA[k]));
  EXPECT_EQ(built(build_sync_write(550, 2, ids, goal, out), out),
            "FF FF FD 00 FE 13 00 83 26 02 02 00 01 64 00 02 38 FF 03 2C 01 04 70 FE E6 0B");
}

TEST(DxlStuffing, TransmitAddsFdAndGrowsLen) {
  std::array<std::uint8_t, kMaxPacketBytes> out{};
  std::array<std::uint8_t, 4> value{};
  put_le(value, static_cast<std::uint32_t>(-131073));  // FF FF FD FF
  EXPECT_EQ(built(build_write(1, 564, value, out), out),
            "FF FF FD 00 01 0A 00 03 34 02 FF FF FD FD FF 23 51");  // LEN 9 → 10
}

TEST(DxlStuffing, ReceiveRemovesFdWithGarbagePrefix) {
  const auto raw = hex("12 FF 00 FF FF FD 00 01 09 00 55 00 FF FF FD FD FF DA 9E");
  PacketReceiver rx(PacketReceiver::Accept::status);
  rx.feed(raw);
  ASSERT_EQ(rx.next(), RxEvent::packet);
  EXPECT_EQ(rx.dropped_bytes(), 3u);
  Packet p;
  ASSERT_TRUE(decode_packet(rx.packet(), true, p));
  EXPECT_EQ(p.id, 1);
  EXPECT_EQ(p.error.raw, 0);
  EXPECT_EQ(p.param_count + 4u, 8u);  // LEN 8 after unstuffing: INST ERR P[4] CRC[2]
  EXPECT_EQ(static_cast<std::int32_t>(get_le(p.parameters())), -131073);
}

TEST(DxlReceive, CorruptCrcIsReported) {
  auto raw = hex("12 FF 00 FF FF FD 00 01 09 00 55 00 FF FF FD FD FF DA 9F");
  PacketReceiver rx(PacketReceiver::Accept::status);
  rx.feed(raw);
  EXPECT_EQ(rx.next(), RxEvent::corrupt);
  EXPECT_EQ(rx.next(), RxEvent::need_more);
}

TEST(DxlReceive, ParsesStatusValues) {
  const Packet ping =
      receive_one(hex("FF FF FD 00 01 07 00 55 00 06 04 26 65 5D"), PacketReceiver::Accept::status);
  EXPECT_EQ(get_le(ping.parameters().first(2)), 0x0406u);
  EXPECT_EQ(ping.params[2], 0x26);
  const Packet read = receive_one(hex("FF FF FD 00 01 08 00 55 00 A6 00 00 00 8C C0"),
                                  PacketReceiver::Accept::status);
  EXPECT_EQ(get_le(read.parameters()), 166u);
  const Packet empty =
      receive_one(hex("FF FF FD 00 01 04 00 55 00 A1 0C"), PacketReceiver::Accept::status);
  EXPECT_EQ(empty.param_count, 0);
  const Packet state =
      receive_one(hex("FF FF FD 00 01 0E 00 55 00 6A FF D2 04 00 00 51 D4 03 00 43 63"),
                  PacketReceiver::Accept::status);
  ASSERT_EQ(state.param_count, 10);
  EXPECT_EQ(static_cast<std::int16_t>(get_le(state.parameters().subspan(0, 2))), -150);
  EXPECT_EQ(static_cast<std::int32_t>(get_le(state.parameters().subspan(2, 4))), 1234);
  EXPECT_EQ(static_cast<std::int32_t>(get_le(state.parameters().subspan(6, 4))), 250961);
}

TEST(DxlReceive, DeviceSideParsesInstructions) {
  const Packet p = receive_one(hex("FF FF FD 00 01 0A 00 03 34 02 FF FF FD FD FF 23 51"),
                               PacketReceiver::Accept::instructions);
  EXPECT_EQ(p.instruction, Instruction::write);
  ASSERT_EQ(p.param_count, 6);
  EXPECT_EQ(get_le(p.parameters().first(2)), 564u);
  EXPECT_EQ(static_cast<std::int32_t>(get_le(p.parameters().subspan(2, 4))), -131073);
}

TEST(DxlReceive, ResyncsOnRejectedHeadersAndSplitInput) {
  // RSRV ≠ 0, LEN > 1024 and INST ≠ 0x55 candidates are dropped byte by byte; the real packet
  // arrives one byte at a time.
  auto raw =
      hex("FF FF FD 01 01 04 00 55 FF FF FD 00 01 FF 7F 55 FF FF FD 00 01 04 00 03 "
          "FF FF FD 00 01 04 00 55 00 A1 0C");
  PacketReceiver rx(PacketReceiver::Accept::status);
  RxEvent last = RxEvent::need_more;
  for (const std::uint8_t b : raw) {
    ASSERT_EQ(last, RxEvent::need_more);
    rx.feed(std::span(&b, 1));
    last = rx.next();
  }
  EXPECT_EQ(last, RxEvent::packet);
  EXPECT_EQ(rx.packet().size(), 11u);
  EXPECT_EQ(rx.dropped_bytes(), raw.size() - 11);
}

TEST(DxlReceive, StuffedHeaderInsideDataIsNotAHeader) {
  // FF FF FD FD in garbage must not be taken as a packet start.
  const Packet p = receive_one(hex("FF FF FD FD 00 FF FF FD 00 01 04 00 55 00 A1 0C"),
                               PacketReceiver::Accept::status);
  EXPECT_EQ(p.id, 1);
}

}  // namespace
}  // namespace tpf::dxl
