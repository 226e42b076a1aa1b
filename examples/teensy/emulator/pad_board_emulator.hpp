// Emulated Teensy pad board on a pseudo-terminal: streams framed pressures at 1 kHz and can be
// unplugged and plugged back, corrupt frames, drop frames and start with garbage.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>

#include "dynamixel/serial/pty_pair.hpp"
#include "teensy/protocol/pad_frame.hpp"

namespace tpf::pad {

struct PadBoardEmulatorOptions {
  std::string link_path;  ///< symlink kept pointing at the current pty (a udev SYMLINK)
  int pads = 16;
  double rate_hz = 1000.0;
  double clock_drift_ppm = 0.0;   ///< device micros() runs fast by this much
  int startup_garbage_bytes = 0;  ///< noise sent before the first frame of each connection
  int realtime_priority = 0;      ///< > 0: SCHED_FIFO for the streaming thread (best effort)
  /// Where the pressures come from: called once per frame on the streaming thread, fills
  /// kpa[0..n) and returns n (≤ kMaxPads; `pads` is then ignored), e.g. the digital twin's pads
  /// (TwinMotorPlant::pad_pressures). Empty: the synthetic pressure_kpa(k, t) on `pads` pads.
  std::function<int(std::span<float> kpa)> source;
};

class PadBoardEmulator {
 public:
  explicit PadBoardEmulator(PadBoardEmulatorOptions options);
  ~PadBoardEmulator();
  PadBoardEmulator(const PadBoardEmulator&) = delete;
  PadBoardEmulator& operator=(const PadBoardEmulator&) = delete;

  void start();
  void stop();

  /// Gauge pressure of pad k (0-based) at device time t [s], kPa: 2 + sin(π t + k).
  static float pressure_kpa(int pad, double t) noexcept;

  void corrupt_next_frames(int n) noexcept { corrupt_.fetch_add(n); }
  /// Skips n frames (seq advances, nothing sent), as the Teensy's 120 ms TX-timeout drop.
  void drop_next_frames(int n) noexcept { drop_.fetch_add(n); }
  /// Closes the pty and removes the link: the host's reads fail with EIO, its reopen fails
  /// (ENOENT) until replug().
  void unplug();
  /// A fresh pty behind the same link; seq and micros() restart from 0.
  void replug();
  std::uint64_t frames_sent() const noexcept { return sent_.load(); }

 private:
  void run();
  void plug_locked();

  PadBoardEmulatorOptions options_;
  std::mutex mutex_;  // guards pty_ and boot_ns_
  std::unique_ptr<serial::PtyPair> pty_;
  std::int64_t boot_ns_ = 0;
  std::uint16_t seq_ = 0;
  int garbage_left_ = 0;
  std::atomic<int> corrupt_{0};
  std::atomic<int> drop_{0};
  std::atomic<std::uint64_t> sent_{0};
  std::atomic<bool> running_{false};
  std::thread thread_;
};

}  // namespace tpf::pad
