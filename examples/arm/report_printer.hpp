// Human-readable loop report (stdout of the example programs).
#pragma once

#include <cstdio>

#include "arm/arm_loop.hpp"

namespace tpf::arm {

/// Prints timing (period jitter p50/p99/max, bus time per cycle) and every fault counter.
void print_report(std::FILE* out, const ArmLoopReport& r, std::size_t motors);

}  // namespace tpf::arm
