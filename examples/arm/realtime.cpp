#include "arm/realtime.hpp"

#include <sched.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>

namespace tpf::arm {

bool enter_realtime(int priority, std::string& message) {
  message.clear();
  if (::mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
    message = std::string("mlockall failed (") + std::strerror(errno) + "); ";
  sched_param param{};
  param.sched_priority = priority;
  if (::sched_setscheduler(0, SCHED_FIFO, &param) != 0) {
    message += std::string("SCHED_FIFO not permitted (") + std::strerror(errno) +
               "): running with normal priority; grant CAP_SYS_NICE or an rtprio limit";
    return false;
  }
  message += "SCHED_FIFO priority " + std::to_string(priority);
  return true;
}

}  // namespace tpf::arm
