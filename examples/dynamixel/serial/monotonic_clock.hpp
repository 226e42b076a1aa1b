// CLOCK_MONOTONIC time in nanoseconds: the one clock of the hardware examples (never
// CLOCK_REALTIME, which jumps with NTP; see docs/hardware.md pitfall 8).
#pragma once

#include <time.h>

#include <cstdint>

namespace tpf::serial {

/// Nanoseconds on CLOCK_MONOTONIC.
using MonoNs = std::int64_t;

/// t = tv_sec·1e9 + tv_nsec of CLOCK_MONOTONIC.
inline MonoNs monotonic_now() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<MonoNs>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

/// Converts nanoseconds on CLOCK_MONOTONIC to a timespec (for clock_nanosleep TIMER_ABSTIME).
inline timespec to_timespec(MonoNs t) noexcept {
  return timespec{static_cast<time_t>(t / 1'000'000'000), static_cast<long>(t % 1'000'000'000)};
}

/// Milliseconds → nanoseconds.
constexpr MonoNs ms_to_ns(double ms) noexcept {
  return static_cast<MonoNs>(ms * 1e6);
}

}  // namespace tpf::serial
