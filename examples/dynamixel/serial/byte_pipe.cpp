#include "dynamixel/serial/byte_pipe.hpp"

#include <algorithm>
#include <chrono>

namespace tpf::serial {

bool BytePipe::Endpoint::write(std::span<const std::uint8_t> bytes, MonoNs) {
  {
    std::lock_guard lock(pipe_.mutex_);
    if (pipe_.closed_) return false;
    auto& q = pipe_.queue_[1 - side_];
    q.insert(q.end(), bytes.begin(), bytes.end());
  }
  pipe_.readable_.notify_all();
  return true;
}

ReadResult BytePipe::Endpoint::read(std::span<std::uint8_t> out, MonoNs deadline) {
  std::unique_lock lock(pipe_.mutex_);
  auto& q = pipe_.queue_[side_];
  for (;;) {
    if (!q.empty()) {
      const std::size_t n = std::min(out.size(), q.size());
      std::copy_n(q.begin(), n, out.begin());
      q.erase(q.begin(), q.begin() + static_cast<std::ptrdiff_t>(n));
      return {n, false};
    }
    if (pipe_.closed_) return {0, true};
    const MonoNs left = deadline - monotonic_now();
    if (left <= 0) return {0, false};
    pipe_.readable_.wait_for(lock, std::chrono::nanoseconds(left));
  }
}

void BytePipe::Endpoint::discard_input() {
  std::lock_guard lock(pipe_.mutex_);
  pipe_.queue_[side_].clear();
}

void BytePipe::close() {
  {
    std::lock_guard lock(mutex_);
    closed_ = true;
  }
  readable_.notify_all();
}

}  // namespace tpf::serial
