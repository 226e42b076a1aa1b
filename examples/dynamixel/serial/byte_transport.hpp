// The byte stream under a protocol: a serial port, a pseudo-terminal or an in-memory pipe.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "dynamixel/serial/monotonic_clock.hpp"

namespace tpf::serial {

/// Outcome of a read: bytes > 0 received, 0 at the deadline, or the device is gone.
struct ReadResult {
  std::size_t bytes = 0;
  bool disconnected = false;  ///< EOF, EIO or ENODEV: the caller must close and reopen
};

/// A bidirectional byte stream. Implementations never block past the given deadline.
class ByteTransport {
 public:
  virtual ~ByteTransport() = default;

  /// Writes every byte (waiting at most until `deadline`); false if that failed.
  virtual bool write(std::span<const std::uint8_t> bytes, MonoNs deadline) = 0;

  /// Returns the bytes already available; if there are none, waits for some until `deadline`
  /// (CLOCK_MONOTONIC). Never blocks beyond it.
  virtual ReadResult read(std::span<std::uint8_t> out, MonoNs deadline) = 0;

  /// Drops any input not read yet (tcflush(TCIFLUSH) on a tty), as before each transaction.
  virtual void discard_input() = 0;
};

}  // namespace tpf::serial
