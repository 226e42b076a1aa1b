// Background reader for the pad board: opens the port, parses frames, aligns device time to
// CLOCK_MONOTONIC and publishes the latest sample lock-free. Unplug → close, reopen with
// exponential back-off. The control loop only calls latest() and stats(): never blocks.
#pragma once

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>

#include "teensy/host/seqlock_latest.hpp"
#include "teensy/protocol/pad_frame.hpp"

namespace tpf::pad {

/// One pad-board frame on the host time line.
struct PadSample {
  std::uint64_t index = 0;          ///< frames received since start (all connections)
  std::int64_t device_time_ns = 0;  ///< device t_us mapped to host CLOCK_MONOTONIC (ns)
  std::int64_t received_ns = 0;     ///< host CLOCK_MONOTONIC when the frame was parsed
  std::uint8_t n = 0;
  std::uint8_t flags = 0;
  float kpa[kMaxPads] = {};  ///< gauge pressure, kPa
  std::uint32_t contact_mask = 0;
};

/// Counters, readable from any thread.
struct PadReaderStats {
  std::uint64_t frames = 0, lost_frames = 0, crc_errors = 0, cobs_errors = 0, format_errors = 0,
                overlong = 0, startup_bytes = 0, connects = 0, disconnects = 0, open_failures = 0;
  bool connected = false;
  double drift_ppm = 0.0;
};

struct PadReaderOptions {
  std::string path;                  ///< e.g. /dev/ttyACM0 or a udev symlink
  double backoff_initial_ms = 10.0;  ///< first retry after an unplug
  double backoff_max_ms = 500.0;     ///< retries double up to this
  double poll_ms = 20.0;             ///< read wait, bounds the stop() latency
  int realtime_priority = 0;         ///< > 0: SCHED_FIFO for the reader thread (best effort)
};

class PadReader {
 public:
  explicit PadReader(PadReaderOptions options);
  ~PadReader();
  PadReader(const PadReader&) = delete;
  PadReader& operator=(const PadReader&) = delete;

  void start();
  void stop();
  /// Latest frame; false if none yet. Lock-free, bounded.
  bool latest(PadSample& out) const noexcept { return latest_.load(out); }
  PadReaderStats stats() const noexcept;

 private:
  void run();

  PadReaderOptions options_;
  SeqlockLatest<PadSample> latest_;
  SeqlockLatest<PadReaderStats> stats_;
  std::atomic<bool> running_{false};
  std::thread thread_;
};

}  // namespace tpf::pad
