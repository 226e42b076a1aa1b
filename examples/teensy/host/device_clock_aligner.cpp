#include "teensy/host/device_clock_aligner.hpp"

#include <algorithm>
#include <cmath>

namespace tpf::pad {

void DeviceClockAligner::reset() noexcept {
  *this = DeviceClockAligner(block_, forgetting_);
}

double DeviceClockAligner::device_seconds(std::uint32_t device_us) const noexcept {
  std::int64_t wraps = wraps_;
  if (device_us < last_us_ && last_us_ - device_us > 0x80000000u) ++wraps;  // counter wrapped
  const std::int64_t us = wraps * (std::int64_t{1} << 32) + device_us - std::int64_t{first_us_};
  return static_cast<double>(us) * 1e-6;
}

void DeviceClockAligner::add(std::uint32_t device_us, std::int64_t host_ns) noexcept {
  if (!started_) {
    started_ = true;
    first_us_ = last_us_ = device_us;
    first_host_ns_ = host_ns;
  }
  const double x = device_seconds(device_us);
  if (device_us < last_us_ && last_us_ - device_us > 0x80000000u) ++wraps_;
  last_us_ = device_us;
  const double y = static_cast<double>(host_ns - first_host_ns_) * 1e-9 - x;  // host − device
  if (in_block_ == 0 || y < block_y_) {
    block_x_ = x;
    block_y_ = y;
  }
  if (!have_offset_) {  // usable immediately: offset from the first sample
    have_offset_ = true;
    offset_ = y;
    x_ref_ = x;
  }
  if (++in_block_ >= block_) close_block();
}

void DeviceClockAligner::close_block() noexcept {
  s0_ = forgetting_ * s0_ + 1.0;
  sx_ = forgetting_ * sx_ + block_x_;
  sy_ = forgetting_ * sy_ + block_y_;
  sxx_ = forgetting_ * sxx_ + block_x_ * block_x_;
  sxy_ = forgetting_ * sxy_ + block_x_ * block_y_;
  ++blocks_;
  in_block_ = 0;
  const double mx = sx_ / s0_;
  const double my = sy_ / s0_;
  const double var = sxx_ / s0_ - mx * mx;
  x_ref_ = mx;
  offset_ = my;
  drift_ = (blocks_ >= 3 && var > 1e-12) ? (sxy_ / s0_ - mx * my) / var : 0.0;
  drift_ = std::clamp(drift_, -kMaxDriftPpm * 1e-6, kMaxDriftPpm * 1e-6);
}

std::int64_t DeviceClockAligner::to_host_ns(std::uint32_t device_us) const noexcept {
  const double x = device_seconds(device_us);
  const double host_s = x + offset_ + drift_ * (x - x_ref_);
  return first_host_ns_ + static_cast<std::int64_t>(std::llround(host_s * 1e9));
}

}  // namespace tpf::pad
