#include "teensy/emulator/pad_board_emulator.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "dynamixel/serial/monotonic_clock.hpp"
#include "dynamixel/serial/thread_priority.hpp"

namespace tpf::pad {

using serial::MonoNs;
using serial::monotonic_now;

PadBoardEmulator::PadBoardEmulator(PadBoardEmulatorOptions options) : options_(std::move(options)) {
  std::lock_guard lock(mutex_);
  plug_locked();
}

PadBoardEmulator::~PadBoardEmulator() {
  stop();
  ::unlink(options_.link_path.c_str());
}

float PadBoardEmulator::pressure_kpa(int pad, double t) noexcept {
  return static_cast<float>(2.0 + std::sin(std::numbers::pi * t + pad));
}

void PadBoardEmulator::plug_locked() {
  pty_ = std::make_unique<serial::PtyPair>();
  boot_ns_ = monotonic_now();
  seq_ = 0;
  garbage_left_ = options_.startup_garbage_bytes;
  // Replace the link atomically, as udev would.
  const std::string tmp = options_.link_path + ".tmp";
  ::unlink(tmp.c_str());
  if (::symlink(pty_->slave_path().c_str(), tmp.c_str()) == 0)
    ::rename(tmp.c_str(), options_.link_path.c_str());
}

void PadBoardEmulator::unplug() {
  std::lock_guard lock(mutex_);
  ::unlink(options_.link_path.c_str());  // udev removes the symlink; the pts number may be reused
  pty_.reset();
}

void PadBoardEmulator::replug() {
  std::lock_guard lock(mutex_);
  plug_locked();
}

void PadBoardEmulator::start() {
  if (running_.exchange(true)) return;
  thread_ = std::thread([this] {
    serial::set_current_thread_fifo(options_.realtime_priority);
    run();
  });
}

void PadBoardEmulator::stop() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
}

void PadBoardEmulator::run() {
  const MonoNs period = static_cast<MonoNs>(1e9 / options_.rate_hz);
  MonoNs next = monotonic_now();
  std::uint32_t noise = 12345;
  std::uint8_t wire[kMaxWireBytes];
  while (running_.load(std::memory_order_relaxed)) {
    next += period;
    const timespec wake = serial::to_timespec(next);
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr);

    std::lock_guard lock(mutex_);
    if (!pty_) continue;                      // unplugged: nothing on the wire
    const MonoNs deadline = monotonic_now();  // never block: drop like the Teensy does
    for (; garbage_left_ > 0; --garbage_left_) {
      noise = noise * 1664525u + 1013904223u;
      const auto b = static_cast<std::uint8_t>((noise >> 24) | 1);  // no 0x00: one run of noise
      pty_->master().write(std::span(&b, 1), deadline);
    }
    const double device_s = static_cast<double>(monotonic_now() - boot_ns_) * 1e-9 *
                            (1.0 + options_.clock_drift_ppm * 1e-6);
    PadFrame frame;
    frame.seq = seq_++;
    frame.t_us = static_cast<std::uint32_t>(static_cast<std::uint64_t>(device_s * 1e6));
    int pads = options_.pads;
    if (options_.source)
      pads = std::clamp(options_.source(std::span(frame.kpa)), 0, static_cast<int>(kMaxPads));
    else
      for (int k = 0; k < pads; ++k)
        frame.kpa[k] = pressure_kpa(k, device_s);
    frame.n = static_cast<std::uint8_t>(pads);
    for (int k = 0; k < pads; ++k)
      if (frame.kpa[k] > 2.5f) frame.contact_mask |= 1u << k;
    if (drop_.load() > 0) {
      drop_.fetch_sub(1);
      continue;
    }
    std::size_t n = encode_frame(frame, wire);
    const bool corrupt = corrupt_.load() > 0;
    if (corrupt) wire[n / 2] = static_cast<std::uint8_t>(wire[n / 2] == 0x55 ? 0x56 : 0x55);
    // A frame that does not fit (host not reading) is lost; a requested corruption then goes to
    // the next frame that reaches the wire, so each one is seen by the host.
    if (pty_->master().write(std::span(wire, n), deadline)) {
      sent_.fetch_add(1);
      if (corrupt) corrupt_.fetch_sub(1);
    }
  }
}

}  // namespace tpf::pad
