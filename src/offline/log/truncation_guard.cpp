#include "offline/log/truncation_guard.hpp"

#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <mutex>

namespace tpf::offline {
namespace {

/// One watched mapping; `begin` is 0 while the slot is free or being filled.
struct WatchedMapping {
  std::atomic<bool> taken{false};
  std::atomic<std::uintptr_t> begin{0};
  std::atomic<std::size_t> bytes{0};
  std::atomic<bool> truncated{false};
};

WatchedMapping watched_mappings[TruncationGuard::kMaxWatched];
struct sigaction bus_error_before {};
std::uintptr_t page_bytes = 4096;

/// Maps zero pages over the watched mapping from the page of `address` on; false if `address`
/// is in no watched mapping.
bool zero_fill_past_end(std::uintptr_t address) noexcept {
  for (WatchedMapping& m : watched_mappings) {
    const std::uintptr_t begin = m.begin.load(std::memory_order_acquire);
    const std::size_t bytes = m.bytes.load(std::memory_order_relaxed);
    if (begin == 0 || address < begin || address - begin >= bytes) continue;
    const std::uintptr_t page = address & ~(page_bytes - 1);
    void* zeros = ::mmap(reinterpret_cast<void*>(page), begin + bytes - page, PROT_READ,
                         MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0);
    if (zeros == MAP_FAILED) return false;
    m.truncated.store(true, std::memory_order_relaxed);
    return true;
  }
  return false;
}

/// SIGBUS: a watched mapping's page past the file's end becomes zeros and the read resumes;
/// any other fault goes to the previous handler, or (default or ignored) ends the process as
/// the kernel would have: the default action back, the faulting access repeats.
void on_bus_error(int signal, siginfo_t* info, void* context) {
  if (zero_fill_past_end(reinterpret_cast<std::uintptr_t>(info->si_addr))) return;
  if ((bus_error_before.sa_flags & SA_SIGINFO) != 0 && bus_error_before.sa_sigaction != nullptr) {
    bus_error_before.sa_sigaction(signal, info, context);
    return;
  }
  if (bus_error_before.sa_handler != SIG_DFL && bus_error_before.sa_handler != SIG_IGN) {
    bus_error_before.sa_handler(signal);
    return;
  }
  struct sigaction fallback {};
  fallback.sa_handler = SIG_DFL;
  ::sigaction(SIGBUS, &fallback, nullptr);
}

void install_bus_error_handler() {
  static std::once_flag once;
  std::call_once(once, [] {
    page_bytes = static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE));
    struct sigaction action {};
    action.sa_sigaction = on_bus_error;
    action.sa_flags = SA_SIGINFO;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGBUS, &action, &bus_error_before);
  });
}

}  // namespace

bool TruncationGuard::watch(const void* begin, std::size_t bytes) noexcept {
  unwatch();
  try {
    install_bus_error_handler();
  } catch (...) {  // std::call_once may throw std::system_error
    return false;
  }
  for (int s = 0; s < kMaxWatched; ++s) {
    WatchedMapping& m = watched_mappings[s];
    bool free = false;
    if (!m.taken.compare_exchange_strong(free, true)) continue;
    m.truncated.store(false, std::memory_order_relaxed);
    m.bytes.store(bytes, std::memory_order_relaxed);
    m.begin.store(reinterpret_cast<std::uintptr_t>(begin), std::memory_order_release);
    slot_ = s;
    return true;
  }
  return false;
}

void TruncationGuard::unwatch() noexcept {
  if (slot_ < 0) return;
  WatchedMapping& m = watched_mappings[slot_];
  m.begin.store(0, std::memory_order_release);
  m.taken.store(false, std::memory_order_release);
  slot_ = -1;
}

bool TruncationGuard::truncated() const noexcept {
  return slot_ >= 0 && watched_mappings[slot_].truncated.load(std::memory_order_relaxed);
}

}  // namespace tpf::offline
