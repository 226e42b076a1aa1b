// A mapped file that another program truncates while it is read: the pages past its new end
// raise SIGBUS. The guard turns them into zero pages and records it, so the reader finishes and
// names the file instead of the process dying.
#pragma once

#include <cstddef>

namespace tpf::offline {

/// Watches one read-only mapping of a file for the file shrinking under it. Touching a page past
/// the file's new end raises SIGBUS; the handler (installed once per process, on the first
/// watch) maps zero pages over the rest of the watched mapping and marks it truncated, so the
/// read goes on and its caller reports the file. A SIGBUS anywhere else goes to the handler that
/// was there before (the default one: the process ends as it would have without the guard).
class TruncationGuard {
 public:
  /// Mappings watched at a time, over the whole process.
  static constexpr int kMaxWatched = 64;

  TruncationGuard() = default;
  ~TruncationGuard() { unwatch(); }
  TruncationGuard(const TruncationGuard&) = delete;
  TruncationGuard& operator=(const TruncationGuard&) = delete;

  /// Starts watching [begin, begin + bytes), a mapping made with mmap; false when kMaxWatched
  /// mappings are already watched (the caller then reads the file instead of mapping it).
  bool watch(const void* begin, std::size_t bytes) noexcept;
  /// Stops watching (before the mapping is unmapped).
  void unwatch() noexcept;
  /// Whether a page of the mapping was found past the file's end (read as zeros since).
  bool truncated() const noexcept;

 private:
  int slot_ = -1;
};

}  // namespace tpf::offline
