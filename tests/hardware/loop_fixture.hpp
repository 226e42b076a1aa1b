// Shared by the end-to-end loop tests against emulated devices (arm_loop, twin_arm_loop).
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace tpf::test {

/// Device threads ask for SCHED_FIFO (best effort) to keep up on a loaded machine; the tests'
/// asserts hold without it too, only with more failed cycles.
inline constexpr int kDevicePriority = 20;

/// CPU time the hypervisor has taken from this virtual machine since boot, summed over its CPUs
/// [s] ("steal" of /proc/stat's cpu line); 0 where the kernel does not count it. A real-time loop
/// loses its periods while its CPU is stolen, whatever its priority.
inline double stolen_cpu_seconds() {
  std::ifstream stat("/proc/stat");
  std::string cpu;
  unsigned long long user, nice, system, idle, iowait, irq, softirq, steal;
  if (!(stat >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal) ||
      cpu != "cpu")
    return 0.0;
  return static_cast<double>(steal) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

/// A path of this process in $TMPDIR (else /tmp): tpf_<tag>_<name>_<pid>.
inline std::string temp_path(const std::string& tag, const std::string& name) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/tpf_" + tag + "_" + name + "_" +
         std::to_string(::getpid());
}

/// A file at temp_path(tag, name), removed when this object goes.
class TempFile {
 public:
  TempFile(const std::string& tag, const std::string& name) : path_(temp_path(tag, name)) {}
  ~TempFile() { std::remove(path_.c_str()); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace tpf::test
