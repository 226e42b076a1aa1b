// Host-side stream parsing (hardware.md §5.2) and device-clock alignment, without threads.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "teensy/host/device_clock_aligner.hpp"
#include "teensy/host/pad_stream_parser.hpp"

namespace tpf::pad {
namespace {

std::vector<std::uint8_t> wire_of(std::uint16_t seq, int pads = 4) {
  PadFrame f;
  f.seq = seq;
  f.t_us = 1000u * seq;
  f.n = static_cast<std::uint8_t>(pads);
  for (int k = 0; k < pads; ++k)
    f.kpa[k] = 0.5f * k + seq;
  std::vector<std::uint8_t> w(kMaxWireBytes);
  w.resize(encode_frame(f, w.data()));
  return w;
}

void append(std::vector<std::uint8_t>& s, const std::vector<std::uint8_t>& more) {
  s.insert(s.end(), more.begin(), more.end());
}

TEST(PadStreamParser, ArbitraryChunkingAfterStartupGarbage) {
  std::vector<std::uint8_t> stream = {0x37, 0x11, 0x00, 0x00};  // garbage, then an empty frame
  for (std::uint16_t s = 0; s < 50; ++s)
    append(stream, wire_of(s));
  std::mt19937 rng(7);
  PadStreamParser parser;
  std::vector<PadFrame> frames;
  for (std::size_t at = 0; at < stream.size();) {
    const std::size_t n = std::min<std::size_t>(stream.size() - at, 1 + rng() % 40);
    parser.feed(std::span(stream).subspan(at, n), [&](const PadFrame& f) { frames.push_back(f); });
    at += n;
  }
  ASSERT_EQ(frames.size(), 50u);
  for (std::uint16_t s = 0; s < 50; ++s) {
    EXPECT_EQ(frames[s].seq, s);
    EXPECT_EQ(frames[s].kpa[3], 1.5f + s);
  }
  EXPECT_EQ(parser.counters().startup_bytes, 2u);
  EXPECT_EQ(parser.counters().empty_frames, 1u);
  EXPECT_EQ(parser.counters().lost_frames, 0u);
}

TEST(PadStreamParser, CountsAndDropsBadFrames) {
  std::vector<std::uint8_t> stream = {0x00};
  append(stream, wire_of(0));
  auto crc_bad = wire_of(1);
  crc_bad[5] = crc_bad[5] == 0x55 ? 0x56 : 0x55;
  append(stream, crc_bad);
  append(stream, {0x09, 0x01, 0x00});                   // COBS code points past the end
  append(stream, std::vector<std::uint8_t>(400, 0x7));  // over-long, no delimiter …
  stream.push_back(0x00);                               // … dropped at the delimiter
  append(stream, wire_of(5));                           // frames 1..4 lost
  append(stream, wire_of(6));
  PadStreamParser parser;
  std::vector<std::uint16_t> seqs;
  parser.feed(stream, [&](const PadFrame& f) { seqs.push_back(f.seq); });
  EXPECT_EQ(seqs, (std::vector<std::uint16_t>{0, 5, 6}));
  const ParserCounters& c = parser.counters();
  EXPECT_EQ(c.crc_errors, 1u);
  EXPECT_EQ(c.cobs_errors, 1u);
  EXPECT_EQ(c.overlong, 1u);
  EXPECT_EQ(c.lost_frames, 4u);
  EXPECT_EQ(c.frames, 3u);
}

TEST(PadStreamParser, SequenceWrapIsNotAGapAndResyncForgetsIt) {
  PadStreamParser parser;
  std::vector<std::uint8_t> stream = {0x00};
  append(stream, wire_of(65535));
  append(stream, wire_of(0));
  parser.feed(stream, [](const PadFrame&) {});
  EXPECT_EQ(parser.counters().lost_frames, 0u);
  parser.resync();  // reconnect: the device restarts at seq 0 after garbage
  std::vector<std::uint8_t> again = {0xAB, 0x00};
  append(again, wire_of(0));
  int frames = 0;
  parser.feed(again, [&](const PadFrame&) { ++frames; });
  EXPECT_EQ(frames, 1);
  EXPECT_EQ(parser.counters().lost_frames, 0u);
  EXPECT_EQ(parser.counters().startup_bytes, 1u);
}

TEST(PadStreamParser, WrongCountWithValidCrcIsAFormatError) {
  PadFrame f;
  f.n = 2;
  std::uint8_t raw[kMaxFrameBytes];
  std::size_t size = serialize_frame(f, raw);
  raw[8] = 3;  // claims 3 pads in a 2-pad frame; re-seal the CRC
  detail::put_u16(raw + size - 2, crc16_ccitt(raw, size - 2));
  std::vector<std::uint8_t> stream(kMaxWireBytes + 1);
  stream[0] = 0x00;
  const std::size_t n = cobs_encode(raw, size, stream.data() + 1);
  stream.resize(n + 1);
  stream.push_back(0x00);
  PadStreamParser parser;
  parser.feed(stream, [](const PadFrame&) { FAIL(); });
  EXPECT_EQ(parser.counters().format_errors, 1u);
}

TEST(DeviceClockAligner, RecoversOffsetAndDriftUnderJitter) {
  // host = 5 s + device·(1 + 80e-6) + delay, delay ∈ [100 µs, 2 ms] (USB and scheduling).
  DeviceClockAligner aligner(100, 0.98);
  std::mt19937 rng(3);
  std::exponential_distribution<double> jitter(1.0 / 300e-6);
  const double drift = 80e-6;
  for (int k = 0; k < 20000; ++k) {  // 20 s at 1 kHz
    const double device_s = k * 1e-3;
    const double host_s = 5.0 + device_s * (1 + drift) + 100e-6 + std::min(jitter(rng), 2e-3);
    aligner.add(static_cast<std::uint32_t>(k * 1000), static_cast<std::int64_t>(host_s * 1e9));
  }
  ASSERT_TRUE(aligner.ready());
  EXPECT_NEAR(aligner.drift_ppm(), 80.0, 5.0);
  const double device_s = 19.999;
  const double true_host = 5.0 + device_s * (1 + drift) + 100e-6;  // minimum-delay arrival
  EXPECT_NEAR(aligner.to_host_ns(19'999'000) * 1e-9, true_host, 50e-6);
}

TEST(DeviceClockAligner, UnwrapsTheMicrosecondCounter) {
  DeviceClockAligner aligner(10, 0.9);
  const std::uint32_t start = 0xFFFFFFFFu - 5000;  // wraps after 5 ms
  for (int k = 0; k < 100; ++k)
    aligner.add(start + 1000u * k, 1'000'000'000 + 1'000'000LL * k + 200'000);
  EXPECT_NEAR(aligner.drift_ppm(), 0.0, 1.0);
  EXPECT_NEAR(static_cast<double>(aligner.to_host_ns(start + 99'000u)),
              1'000'000'000 + 99'200'000.0, 1e3);
}

}  // namespace
}  // namespace tpf::pad
