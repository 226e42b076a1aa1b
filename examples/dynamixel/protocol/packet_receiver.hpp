// Receive state machine of Protocol 2.0, as SDK rxPacket: finds FF FF FD xx (xx ≠ FD), rejects a
// candidate with RSRV ≠ 0, LEN > 1024 or an unexpected INST by dropping one byte and rescanning,
// waits for LEN + 7 bytes and checks the CRC over the still-stuffed bytes.
#pragma once

#include <array>

#include "dynamixel/protocol/packet.hpp"

namespace tpf::dxl {

enum class RxEvent : std::uint8_t {
  need_more,  ///< no complete packet buffered yet
  packet,     ///< packet() holds a CRC-valid packet
  corrupt,    ///< packet() holds a complete packet whose CRC does not match; it is dropped
};

/// Accumulates bytes and cuts them into packets. No allocation; bounded buffer.
class PacketReceiver {
 public:
  /// Host side accepts only status packets (INST 0x55); device side only instructions.
  enum class Accept : std::uint8_t { status, instructions };

  explicit PacketReceiver(Accept accept) noexcept : accept_(accept) {}

  /// Free space to read into; after reading n bytes there, call commit(n).
  std::span<std::uint8_t> write_area() noexcept;
  void commit(std::size_t n) noexcept { size_ += n; }
  /// Copies as many bytes as fit; returns how many were taken.
  std::size_t feed(std::span<const std::uint8_t> bytes) noexcept;

  /// Advances the state machine over the buffered bytes.
  RxEvent next() noexcept;
  /// Raw bytes (header … CRC) of the packet reported by the last next().
  std::span<const std::uint8_t> packet() const noexcept { return {buffer_.data(), consumed_}; }

  /// Forgets everything buffered (before a new transaction).
  void clear() noexcept { size_ = consumed_ = 0; }
  /// Bytes discarded while resynchronising (garbage, rejected headers, corrupt packets).
  std::size_t dropped_bytes() const noexcept { return dropped_; }

 private:
  void drop_front(std::size_t n, bool garbage) noexcept;
  bool accepts(std::uint8_t inst) const noexcept;

  Accept accept_;
  std::array<std::uint8_t, 2 * kMaxPacketBytes> buffer_{};
  std::size_t size_ = 0;
  std::size_t consumed_ = 0;  ///< bytes of the packet last returned, dropped on the next call
  std::size_t dropped_ = 0;
};

}  // namespace tpf::dxl
