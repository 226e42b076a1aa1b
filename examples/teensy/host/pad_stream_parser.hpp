// Cuts the pad board's byte stream into frames (hardware.md §5.2): arbitrary chunking, start-up
// garbage, over-long frames, COBS/CRC/format errors and sequence gaps are counted, never fatal.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "teensy/protocol/pad_frame.hpp"

namespace tpf::pad {

struct ParserCounters {
  std::uint64_t frames = 0;         ///< valid frames delivered
  std::uint64_t startup_bytes = 0;  ///< discarded before the first delimiter after (re)connect
  std::uint64_t empty_frames = 0;   ///< "00 00"
  std::uint64_t overlong = 0;       ///< accumulations longer than kMaxWireBytes, dropped
  std::uint64_t cobs_errors = 0;
  std::uint64_t crc_errors = 0;
  std::uint64_t format_errors = 0;  ///< version, type or length against n
  std::uint64_t lost_frames = 0;    ///< sum of sequence gaps
};

/// Byte-stream → PadFrame. No allocation; the callback runs inside feed().
class PadStreamParser {
 public:
  /// Feeds any chunk; calls on_frame(const PadFrame&) for each valid frame, in order.
  template <typename OnFrame>
  void feed(std::span<const std::uint8_t> bytes, OnFrame&& on_frame) {
    for (const std::uint8_t b : bytes)
      if (push(b)) on_frame(static_cast<const PadFrame&>(frame_));
  }

  /// After a reconnect: discard up to the next delimiter, forget the sequence number.
  void resync() noexcept;
  const ParserCounters& counters() const noexcept { return counters_; }

 private:
  /// True when `b` completed a valid frame (in frame_).
  bool push(std::uint8_t b) noexcept;
  bool finish_frame() noexcept;

  std::array<std::uint8_t, kMaxWireBytes> encoded_{};
  std::size_t size_ = 0;
  bool synced_ = false;
  bool overlong_ = false;
  bool have_seq_ = false;
  std::uint16_t last_seq_ = 0;
  PadFrame frame_{};
  ParserCounters counters_{};
};

}  // namespace tpf::pad
