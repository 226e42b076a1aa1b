// ByteTransport over a non-blocking file descriptor (tty, pty master), with poll() and deadlines.
#pragma once

#include "dynamixel/serial/byte_transport.hpp"

namespace tpf::serial {

/// Owns a non-blocking fd; reads and writes wait with poll() until a CLOCK_MONOTONIC deadline.
class FdTransport : public ByteTransport {
 public:
  FdTransport() = default;
  explicit FdTransport(int fd) noexcept : fd_(fd) {}
  ~FdTransport() override { close(); }
  FdTransport(FdTransport&& other) noexcept : fd_(other.release()) {}
  FdTransport& operator=(FdTransport&& other) noexcept;
  FdTransport(const FdTransport&) = delete;
  FdTransport& operator=(const FdTransport&) = delete;

  bool write(std::span<const std::uint8_t> bytes, MonoNs deadline) override;
  ReadResult read(std::span<std::uint8_t> out, MonoNs deadline) override;
  void discard_input() override;

  bool is_open() const noexcept { return fd_ >= 0; }
  int fd() const noexcept { return fd_; }
  /// Closes the descriptor (idempotent).
  void close() noexcept;
  /// Gives up ownership of the descriptor.
  int release() noexcept {
    int fd = fd_;
    fd_ = -1;
    return fd;
  }

 private:
  int fd_ = -1;
};

}  // namespace tpf::serial
