// Test helper: polls a condition every millisecond until it holds or a bound passes.
#pragma once

#include <time.h>

namespace tpf::test {

/// True as soon as `condition()` holds; false after `timeout_s` (bounded, never hangs).
template <typename Condition>
bool wait_until(Condition&& condition, double timeout_s = 3.0) {
  timespec start{};
  clock_gettime(CLOCK_MONOTONIC, &start);
  for (;;) {
    if (condition()) return true;
    timespec now{};
    clock_gettime(CLOCK_MONOTONIC, &now);
    if ((now.tv_sec - start.tv_sec) + 1e-9 * (now.tv_nsec - start.tv_nsec) > timeout_s)
      return false;
    const timespec pause{0, 1'000'000};
    clock_nanosleep(CLOCK_MONOTONIC, 0, &pause, nullptr);
  }
}

}  // namespace tpf::test
