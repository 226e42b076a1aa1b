// Single-writer "latest value" cell (a seqlock): the writer never waits, readers never block the
// writer and retry only while a write is in flight. The payload is stored in relaxed atomic
// words, so the pattern is free of data races (Boehm, "Can seqlocks get along with programming
// language memory models?", 2012).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace tpf::pad {

template <typename T>
class SeqlockLatest {
  static_assert(std::is_trivially_copyable_v<T>);
  static constexpr std::size_t kWords = (sizeof(T) + 7) / 8;

 public:
  /// Writer (one thread only): seq odd → payload → seq even.
  void store(const T& value) noexcept {
    std::array<std::uint64_t, kWords> words{};
    std::memcpy(words.data(), &value, sizeof(T));
    const std::uint64_t s = seq_.load(std::memory_order_relaxed);
    seq_.store(s + 1, std::memory_order_relaxed);
    std::atomic_thread_fence(std::memory_order_release);
    for (std::size_t i = 0; i < kWords; ++i)
      words_[i].store(words[i], std::memory_order_relaxed);
    seq_.store(s + 2, std::memory_order_release);
  }

  /// Reader: copies a consistent value into `out`. False if nothing was stored yet or if the
  /// writer kept it busy for `max_attempts` tries (bounded: never blocks the caller).
  bool load(T& out, int max_attempts = 64) const noexcept {
    for (int attempt = 0; attempt < max_attempts; ++attempt) {
      const std::uint64_t s1 = seq_.load(std::memory_order_acquire);
      if (s1 == 0) return false;
      if (s1 & 1) continue;
      std::array<std::uint64_t, kWords> words;
      for (std::size_t i = 0; i < kWords; ++i)
        words[i] = words_[i].load(std::memory_order_relaxed);
      std::atomic_thread_fence(std::memory_order_acquire);
      if (seq_.load(std::memory_order_relaxed) == s1) {
        std::memcpy(static_cast<void*>(&out), words.data(), sizeof(T));
        return true;
      }
    }
    return false;
  }

 private:
  std::atomic<std::uint64_t> seq_{0};
  std::array<std::atomic<std::uint64_t>, kWords> words_{};
};

}  // namespace tpf::pad
