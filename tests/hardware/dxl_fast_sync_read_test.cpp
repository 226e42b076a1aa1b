// Fast Sync Read responses of hardware.md §1.5–1.6: unstuffed layout and running block CRCs.
#include <gtest/gtest.h>

#include <array>

#include "dynamixel/protocol/fast_sync_read.hpp"
#include "dynamixel/protocol/packet_receiver.hpp"
#include "hex.hpp"

namespace tpf::dxl {
namespace {

using test::hex;
using test::to_hex;

const char* const kThreeDevices =
    "FF FF FD 00 FE 19 00 55 00 03 A6 00 00 00 84 08 00 07 1F 08 00 00 16 CA 00 04 FF 03 00 00 D1 "
    "9E";
const char* const kPh54FourDevices =
    "FF FF FD 00 FE 39 00 55 00 01 64 00 D2 04 00 00 51 D4 03 00 FB CE 00 02 38 FF CE FF FF FF 18 "
    "FC "
    "FF FF E6 C9 00 03 00 00 00 00 00 00 00 00 00 00 42 E2 00 04 1C 3E 68 0B 00 00 A3 A8 07 00 2C "
    "E4";

TEST(DxlFastSyncRead, ParsesEmanualThreeDeviceResponse) {
  const auto raw = hex(kThreeDevices);
  PacketReceiver rx(PacketReceiver::Accept::status);
  rx.feed(raw);
  ASSERT_EQ(rx.next(), RxEvent::packet);
  const std::uint8_t ids[] = {3, 7, 4};
  std::array<std::uint8_t, 12> data{};
  std::array<StatusError, 3> errors{};
  ASSERT_TRUE(parse_fast_sync_read(rx.packet(), 4, ids, data, errors));
  EXPECT_EQ(get_le(std::span(data).subspan(0, 4)), 166u);
  EXPECT_EQ(get_le(std::span(data).subspan(4, 4)), 2079u);
  EXPECT_EQ(get_le(std::span(data).subspan(8, 4)), 1023u);
  for (const auto e : errors)
    EXPECT_EQ(e.raw, 0);
}

TEST(DxlFastSyncRead, BuildsRunningBlockCrcs) {
  const std::uint8_t ids[] = {3, 7, 4};
  std::array<std::uint8_t, 12> data{};
  put_le(std::span(data).subspan(0, 4), 166);
  put_le(std::span(data).subspan(4, 4), 2079);
  put_le(std::span(data).subspan(8, 4), 1023);
  const std::array<StatusError, 3> errors{};
  std::array<std::uint8_t, kMaxPacketBytes> out{};
  const std::size_t n = build_fast_sync_read(4, ids, data, errors, out);
  EXPECT_EQ(to_hex(std::span(out).first(n)), kThreeDevices);  // 84 08, 16 CA, D1 9E
}

TEST(DxlFastSyncRead, Ph54FourDevicesRoundTrip) {
  const auto raw = hex(kPh54FourDevices);
  ASSERT_EQ(raw.size(), 64u);
  PacketReceiver rx(PacketReceiver::Accept::status);
  rx.feed(raw);
  ASSERT_EQ(rx.next(), RxEvent::packet);
  const std::uint8_t ids[] = {1, 2, 3, 4};
  std::array<std::uint8_t, 40> data{};
  std::array<StatusError, 4> errors{};
  ASSERT_TRUE(parse_fast_sync_read(rx.packet(), 10, ids, data, errors));
  const std::int32_t expected[4][3] = {
      {100, 1234, 250961}, {-200, -50, -1000}, {0, 0, 0}, {15900, 2920, 501923}};
  for (int k = 0; k < 4; ++k) {
    const auto block = std::span(data).subspan(10 * k, 10);
    EXPECT_EQ(static_cast<std::int16_t>(get_le(block.subspan(0, 2))), expected[k][0]) << k;
    EXPECT_EQ(static_cast<std::int32_t>(get_le(block.subspan(2, 4))), expected[k][1]) << k;
    EXPECT_EQ(static_cast<std::int32_t>(get_le(block.subspan(6, 4))), expected[k][2]) << k;
  }
  std::array<std::uint8_t, kMaxPacketBytes> out{};
  const std::size_t n = build_fast_sync_read(10, ids, data, errors, out);
  EXPECT_EQ(to_hex(std::span(out).first(n)), kPh54FourDevices);
}

TEST(DxlFastSyncRead, RejectsWrongIdsAndLength) {
  const auto raw = hex(kThreeDevices);
  std::array<std::uint8_t, 16> data{};
  std::array<StatusError, 4> errors{};
  const std::uint8_t wrong_order[] = {3, 4, 7};
  EXPECT_FALSE(parse_fast_sync_read(raw, 4, wrong_order, data, errors));
  const std::uint8_t too_many[] = {3, 7, 4, 5};
  EXPECT_FALSE(parse_fast_sync_read(raw, 4, too_many, data, errors));
}

}  // namespace
}  // namespace tpf::dxl
