// The threaded pad reader against the emulated pad board on a pty: garbage at start, CRC errors,
// dropped frames, unplug and replug with back-off, clock alignment. All waits are bounded.
#include "teensy/host/pad_reader.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <string>

#include "dynamixel/serial/monotonic_clock.hpp"
#include "teensy/emulator/pad_board_emulator.hpp"
#include "wait_until.hpp"

namespace tpf::pad {
namespace {

std::string temp_link(const char* name) {
  return std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") + "/tpf_" + name +
         "_" + std::to_string(::getpid());
}

TEST(PadReader, StreamsAlignedSamplesAndCountsFaults) {
  PadBoardEmulatorOptions options;
  options.link_path = temp_link("pads_a");
  options.startup_garbage_bytes = 33;
  options.clock_drift_ppm = 100.0;
  PadBoardEmulator board(options);
  PadReader reader({options.link_path, 5.0, 100.0, 5.0});
  reader.start();
  // Connected before the board talks, so its start-up noise reaches the parser.
  ASSERT_TRUE(test::wait_until([&] { return reader.stats().connected; }));
  board.start();
  ASSERT_TRUE(test::wait_until([&] { return reader.stats().frames >= 100; }));
  board.corrupt_next_frames(2);
  board.drop_next_frames(5);
  // On a loaded machine the reader can be starved while the pty buffers hundreds of frames: the
  // faults then arrive behind that backlog. Wait (bounded) for their counts, not for a number of
  // frames, and for the reader to drain the backlog.
  const auto faults_seen = [&] {
    const PadReaderStats st = reader.stats();
    return st.crc_errors + st.cobs_errors >= 2 && st.lost_frames >= 5 + 2;
  };
  EXPECT_TRUE(test::wait_until(faults_seen, 20.0));

  PadSample s;
  bool causal = true;
  const auto fresh = [&] {  // the reader is current: the sample was taken < 200 ms ago
    if (!reader.latest(s)) return false;
    causal = causal && s.device_time_ns <= s.received_ns;
    return s.received_ns - s.device_time_ns < 200'000'000;
  };
  ASSERT_TRUE(test::wait_until(fresh, 20.0));
  EXPECT_EQ(s.n, 16);
  for (int k = 0; k < 16; ++k) {
    EXPECT_GE(s.kpa[k], 1.0f);
    EXPECT_LE(s.kpa[k], 3.0f);
  }
  // The device time maps onto the host clock: never after the receive time (causality).
  EXPECT_TRUE(causal);
  const PadReaderStats stats = reader.stats();
  EXPECT_GE(stats.crc_errors + stats.cobs_errors, 2u);
  EXPECT_GE(stats.lost_frames, 5u + 2u);  // dropped and corrupted frames both leave seq gaps
  EXPECT_GE(stats.startup_bytes, 33u);    // the noise and the frame it runs into, up to its 00
  EXPECT_TRUE(stats.connected);
  reader.stop();
  board.stop();
}

TEST(PadReader, ReconnectsWithBackoffAfterUnplug) {
  PadBoardEmulatorOptions options;
  options.link_path = temp_link("pads_b");
  PadBoardEmulator board(options);
  board.start();
  PadReader reader({options.link_path, 5.0, 40.0, 5.0});
  reader.start();
  ASSERT_TRUE(test::wait_until([&] { return reader.stats().frames >= 50; }));
  board.unplug();
  ASSERT_TRUE(test::wait_until([&] { return !reader.stats().connected; }));
  // Reopen attempts fail (the pty is gone) and are retried with growing delays.
  ASSERT_TRUE(test::wait_until([&] { return reader.stats().open_failures >= 3; }));
  PadSample stale;
  ASSERT_TRUE(reader.latest(stale));  // the last sample stays readable while unplugged
  board.replug();
  ASSERT_TRUE(test::wait_until([&] { return reader.stats().connected; }));
  const std::uint64_t before = reader.stats().frames;
  ASSERT_TRUE(test::wait_until([&] { return reader.stats().frames >= before + 50; }));
  const PadReaderStats stats = reader.stats();
  EXPECT_EQ(stats.connects, 2u);
  EXPECT_EQ(stats.disconnects, 1u);
  // Back-off: within ~150 ms of unplug, 5+10+20+40+40… ms gives far fewer than 150 attempts.
  EXPECT_LT(stats.open_failures, 60u);
  PadSample fresh;
  ASSERT_TRUE(reader.latest(fresh));
  EXPECT_GT(fresh.received_ns, stale.received_ns);
  reader.stop();
  board.stop();
}

}  // namespace
}  // namespace tpf::pad
