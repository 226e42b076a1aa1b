// Pad-board framing (hardware.md §5.1): every COBS vector, CRC check values, frame round trip.
#include <gtest/gtest.h>

#include <array>
#include <string_view>

#include "hex.hpp"
#include "teensy/protocol/pad_frame.hpp"

namespace tpf::pad {
namespace {

using test::hex;

std::vector<std::uint8_t> iota_bytes(int first, int last) {
  std::vector<std::uint8_t> v;
  for (int b = first; b <= last; ++b)
    v.push_back(static_cast<std::uint8_t>(b));
  return v;
}

std::vector<std::uint8_t> concat(std::vector<std::uint8_t> a, const std::vector<std::uint8_t>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

void expect_cobs(const std::vector<std::uint8_t>& plain, const std::vector<std::uint8_t>& encoded) {
  std::vector<std::uint8_t> out(cobs_max_encoded_size(plain.size()) + 1);
  const std::size_t n = cobs_encode(plain.data(), plain.size(), out.data());
  out.resize(n);
  EXPECT_EQ(out, encoded) << "encode of " << plain.size() << " bytes";
  EXPECT_LE(n, cobs_max_encoded_size(plain.size()));
  std::vector<std::uint8_t> back(encoded.size());
  std::size_t m = 0;
  ASSERT_TRUE(cobs_decode(encoded.data(), encoded.size(), back.data(), &m));
  back.resize(m);
  EXPECT_EQ(back, plain) << "decode of " << encoded.size() << " bytes";
}

TEST(PadCobs, PublishedVectorsRoundTrip) {
  expect_cobs(hex("00"), hex("01 01"));
  expect_cobs(hex("00 00"), hex("01 01 01"));
  expect_cobs(hex("00 11 00"), hex("01 02 11 01"));
  expect_cobs(hex("11 22 00 33"), hex("03 11 22 02 33"));
  expect_cobs(hex("11 22 33 44"), hex("05 11 22 33 44"));
  expect_cobs(hex("11 00 00 00"), hex("02 11 01 01 01"));
  expect_cobs(iota_bytes(0x01, 0xFE), concat({0xFF}, iota_bytes(0x01, 0xFE)));
  expect_cobs(iota_bytes(0x00, 0xFE), concat({0x01, 0xFF}, iota_bytes(0x01, 0xFE)));
  expect_cobs(iota_bytes(0x01, 0xFF), concat(concat({0xFF}, iota_bytes(0x01, 0xFE)), {0x02, 0xFF}));
}

TEST(PadCobs, RejectsCodesPastTheEnd) {
  std::array<std::uint8_t, 8> out{};
  std::size_t n = 0;
  const auto bad = hex("05 11 22");  // code 5 needs 4 more bytes
  EXPECT_FALSE(cobs_decode(bad.data(), bad.size(), out.data(), &n));
  const auto zero = hex("02 11 00 01");  // a zero inside a frame
  EXPECT_FALSE(cobs_decode(zero.data(), zero.size(), out.data(), &n));
}

TEST(PadCrc, CheckValue) {
  const std::string_view text = "123456789";
  EXPECT_EQ(crc16_ccitt(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()), 0x29B1);
  EXPECT_EQ(kCrc16CcittTable.entry[1], 0x1021);
}

TEST(PadFrame, EncodesLayoutAndRoundTrips) {
  PadFrame f;
  f.seq = 0x1234;
  f.t_us = 0xA1B2C3D4;
  f.n = 2;
  f.flags = kFlagSaturated;
  f.kpa[0] = 1.5f;
  f.kpa[1] = -0.25f;
  f.contact_mask = 0x1;
  std::array<std::uint8_t, kMaxFrameBytes> raw{};
  const std::size_t size = serialize_frame(f, raw.data());
  ASSERT_EQ(size, kFrameOverhead + 8);
  EXPECT_EQ(test::to_hex(std::span(raw).first(14)), "01 01 34 12 D4 C3 B2 A1 02 01 00 00 C0 3F");
  EXPECT_EQ(raw[size - 2] | (raw[size - 1] << 8), crc16_ccitt(raw.data(), size - 2));

  std::array<std::uint8_t, kMaxWireBytes> wire{};
  const std::size_t n = encode_frame(f, wire.data());
  EXPECT_EQ(wire[n - 1], 0x00);
  for (std::size_t i = 0; i + 1 < n; ++i)
    EXPECT_NE(wire[i], 0x00);
  std::array<std::uint8_t, kMaxWireBytes> decoded{};
  std::size_t m = 0;
  ASSERT_TRUE(cobs_decode(wire.data(), n - 1, decoded.data(), &m));
  PadFrame g;
  ASSERT_EQ(parse_frame(decoded.data(), m, g), FrameError::none);
  EXPECT_EQ(g.seq, f.seq);
  EXPECT_EQ(g.t_us, f.t_us);
  EXPECT_EQ(g.n, 2);
  EXPECT_EQ(g.flags, kFlagSaturated);
  EXPECT_EQ(g.kpa[0], 1.5f);
  EXPECT_EQ(g.kpa[1], -0.25f);
  EXPECT_EQ(g.contact_mask, 1u);
}

TEST(PadFrame, RejectsBadCrcVersionAndCount) {
  PadFrame f;
  f.n = 3;
  std::array<std::uint8_t, kMaxFrameBytes> raw{};
  const std::size_t size = serialize_frame(f, raw.data());
  PadFrame g;
  auto bad = raw;
  bad[12] ^= 0x01;
  EXPECT_EQ(parse_frame(bad.data(), size, g), FrameError::crc);
  EXPECT_EQ(parse_frame(raw.data(), size - 4, g), FrameError::crc);
  f.version = 2;
  serialize_frame(f, raw.data());
  EXPECT_EQ(parse_frame(raw.data(), size, g), FrameError::version);
  EXPECT_EQ(parse_frame(raw.data(), 5, g), FrameError::length);
}

}  // namespace
}  // namespace tpf::pad
