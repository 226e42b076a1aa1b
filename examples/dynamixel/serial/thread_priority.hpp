// Best-effort SCHED_FIFO for a device thread (reader, emulator) so that it keeps up on a loaded
// machine; without the permission the thread simply stays at normal priority.
#pragma once

#include <pthread.h>
#include <sched.h>

namespace tpf::serial {

/// Sets the calling thread to SCHED_FIFO `priority` (1–99); priority ≤ 0 does nothing.
/// Returns true if the thread now runs real-time.
inline bool set_current_thread_fifo(int priority) noexcept {
  if (priority <= 0) return false;
  sched_param param{};
  param.sched_priority = priority;
  return pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0;
}

}  // namespace tpf::serial
