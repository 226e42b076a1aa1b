// Maps the pad board's micros() to host CLOCK_MONOTONIC: host = device + a + b·(device − x0).
// Transport delay is non-negative, so the lowest (host − device) per block of samples is the
// cleanest offset estimate (min filter); a + b come from an exponentially weighted least-squares
// line through those block minima (offset and drift).
#pragma once

#include <cstdint>

namespace tpf::pad {

class DeviceClockAligner {
 public:
  /// Largest drift believed [ppm]: quartz clocks stay within ±100 ppm; a steeper line comes from
  /// block minima inflated by a starved reader, and extrapolating it would misplace samples.
  static constexpr double kMaxDriftPpm = 1000.0;

  /// `block` samples per min-filter block (e.g. 100 = 0.1 s at 1 kHz); `forgetting` ∈ (0, 1] is
  /// the weight kept by older blocks per new block.
  explicit DeviceClockAligner(int block = 100, double forgetting = 0.98) noexcept
      : block_(block), forgetting_(forgetting) {}

  /// Adds one frame: device time t_us (wrapping u32) and host receive time in ns.
  void add(std::uint32_t device_us, std::int64_t host_ns) noexcept;
  /// Host CLOCK_MONOTONIC time (ns) of a device time; uses the offset alone until the drift is
  /// known. Call only when ready().
  std::int64_t to_host_ns(std::uint32_t device_us) const noexcept;
  bool ready() const noexcept { return have_offset_; }
  /// Estimated drift of the host clock relative to the device clock, in ppm.
  double drift_ppm() const noexcept { return drift_ * 1e6; }
  /// Forget everything (device reset: micros() restarts).
  void reset() noexcept;

 private:
  /// Unwraps the 32-bit µs counter into seconds since the first sample.
  double device_seconds(std::uint32_t device_us) const noexcept;
  void close_block() noexcept;

  int block_;
  double forgetting_;
  bool started_ = false;
  std::uint32_t first_us_ = 0;
  std::uint32_t last_us_ = 0;
  std::int64_t wraps_ = 0;
  std::int64_t first_host_ns_ = 0;
  // Current block: the sample with the smallest host − device.
  int in_block_ = 0;
  double block_x_ = 0.0, block_y_ = 0.0;
  // Weighted sums over block minima (x: device s, y: offset s).
  double s0_ = 0.0, sx_ = 0.0, sy_ = 0.0, sxx_ = 0.0, sxy_ = 0.0;
  int blocks_ = 0;
  bool have_offset_ = false;
  double offset_ = 0.0, drift_ = 0.0, x_ref_ = 0.0;
};

}  // namespace tpf::pad
