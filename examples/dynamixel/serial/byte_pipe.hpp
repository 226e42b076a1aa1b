// An in-memory, full-duplex byte pipe: two ByteTransport endpoints for tests without a tty.
#pragma once

#include <condition_variable>
#include <deque>
#include <mutex>

#include "dynamixel/serial/byte_transport.hpp"

namespace tpf::serial {

/// Two connected endpoints; what one writes the other reads. Thread-safe. close() makes both
/// ends report `disconnected`, like an unplugged cable.
class BytePipe {
 public:
  class Endpoint : public ByteTransport {
   public:
    bool write(std::span<const std::uint8_t> bytes, MonoNs deadline) override;
    ReadResult read(std::span<std::uint8_t> out, MonoNs deadline) override;
    void discard_input() override;

   private:
    friend class BytePipe;
    Endpoint(BytePipe& pipe, int side) : pipe_(pipe), side_(side) {}
    BytePipe& pipe_;
    int side_;
  };

  BytePipe() : a_(*this, 0), b_(*this, 1) {}
  BytePipe(const BytePipe&) = delete;
  BytePipe& operator=(const BytePipe&) = delete;

  Endpoint& a() noexcept { return a_; }
  Endpoint& b() noexcept { return b_; }
  /// Disconnects both endpoints (pending reads return `disconnected`).
  void close();

 private:
  std::mutex mutex_;
  std::condition_variable readable_;
  std::deque<std::uint8_t> queue_[2];  ///< queue_[s]: bytes waiting to be read by side s
  bool closed_ = false;
  Endpoint a_, b_;
};

}  // namespace tpf::serial
