// Real-time set-up of the calling thread: locked memory and SCHED_FIFO where permitted.
#pragma once

#include <string>

namespace tpf::arm {

/// mlockall(MCL_CURRENT | MCL_FUTURE) and SCHED_FIFO at `priority`. Returns false with a message
/// (e.g. "SCHED_FIFO not permitted (EPERM): running with normal priority") when not allowed; the
/// loop then runs unchanged, only with more jitter.
bool enter_realtime(int priority, std::string& message);

}  // namespace tpf::arm
