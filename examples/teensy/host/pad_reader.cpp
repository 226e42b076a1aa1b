#include "teensy/host/pad_reader.hpp"

#include <algorithm>
#include <array>

#include "dynamixel/serial/serial_port.hpp"
#include "dynamixel/serial/thread_priority.hpp"
#include "teensy/host/device_clock_aligner.hpp"
#include "teensy/host/pad_stream_parser.hpp"
#include "tpf/common/error.hpp"

namespace tpf::pad {

using serial::MonoNs;
using serial::monotonic_now;

PadReader::PadReader(PadReaderOptions options) : options_(std::move(options)) {
  stats_.store(PadReaderStats{});
}

PadReader::~PadReader() {
  stop();
}

void PadReader::start() {
  if (running_.exchange(true)) return;
  thread_ = std::thread([this] {
    serial::set_current_thread_fifo(options_.realtime_priority);
    run();
  });
}

void PadReader::stop() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
}

PadReaderStats PadReader::stats() const noexcept {
  PadReaderStats s;
  stats_.load(s);
  return s;
}

void PadReader::run() {
  PadStreamParser parser;
  DeviceClockAligner clock;
  PadReaderStats stats;
  PadSample sample;
  serial::FdTransport port;
  double backoff_ms = options_.backoff_initial_ms;
  MonoNs next_attempt = 0;
  std::array<std::uint8_t, 4096> chunk{};

  const auto publish_stats = [&] {
    const ParserCounters& c = parser.counters();
    stats.frames = c.frames;
    stats.lost_frames = c.lost_frames;
    stats.crc_errors = c.crc_errors;
    stats.cobs_errors = c.cobs_errors;
    stats.format_errors = c.format_errors;
    stats.overlong = c.overlong;
    stats.startup_bytes = c.startup_bytes;
    stats.connected = port.is_open();
    stats.drift_ppm = clock.drift_ppm();
    stats_.store(stats);
  };

  while (running_.load(std::memory_order_relaxed)) {
    const MonoNs now = monotonic_now();
    if (!port.is_open()) {
      if (now < next_attempt) {
        const MonoNs wait = std::min(next_attempt - now, serial::ms_to_ns(options_.poll_ms));
        const timespec ts = serial::to_timespec(wait);
        clock_nanosleep(CLOCK_MONOTONIC, 0, &ts, nullptr);
        continue;
      }
      try {
        port = serial::open_serial_port(options_.path, 0);  // USB CDC: the baud rate is ignored
        ++stats.connects;
        backoff_ms = options_.backoff_initial_ms;
        parser.resync();  // discard to the first delimiter; seq and t_us restart
        clock.reset();
      } catch (const Error&) {
        ++stats.open_failures;
        next_attempt = now + serial::ms_to_ns(backoff_ms);
        backoff_ms = std::min(2.0 * backoff_ms, options_.backoff_max_ms);
      }
      publish_stats();
      continue;
    }
    const serial::ReadResult r =
        port.read(chunk, monotonic_now() + serial::ms_to_ns(options_.poll_ms));
    if (r.disconnected) {
      port.close();
      ++stats.disconnects;
      next_attempt = monotonic_now() + serial::ms_to_ns(backoff_ms);
      publish_stats();
      continue;
    }
    if (r.bytes == 0) continue;
    const MonoNs received = monotonic_now();
    parser.feed(std::span(chunk).first(r.bytes), [&](const PadFrame& f) {
      clock.add(f.t_us, received);
      sample.index = parser.counters().frames;
      // Causality: a frame was sampled before it arrived. The line fit can put it later when a
      // block's minimum was inflated (the reader starved on a loaded machine).
      sample.device_time_ns = std::min(clock.to_host_ns(f.t_us), received);
      sample.received_ns = received;
      sample.n = f.n;
      sample.flags = f.flags;
      std::copy_n(f.kpa, kMaxPads, sample.kpa);
      sample.contact_mask = f.contact_mask;
      latest_.store(sample);
    });
    publish_stats();
  }
  port.close();
  publish_stats();
}

}  // namespace tpf::pad
