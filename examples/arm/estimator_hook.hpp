// Where the core Estimator runs in the arm loop (a later issue): called once per cycle with the
// cycle's sample, on the real-time thread, after the bus read and before the log.
#pragma once

#include "arm/cycle_sample.hpp"

namespace tpf::arm {

/// Per-cycle estimator entry point. It must not allocate, block or do I/O. Today no estimator is
/// linked, so it does nothing; the core Estimator (tpf::core) will be called from here with
/// q, dq, i and p of `sample`.
void run_estimator_hook(const CycleSample& sample) noexcept;

}  // namespace tpf::arm
