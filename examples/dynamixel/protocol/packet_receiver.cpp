#include "dynamixel/protocol/packet_receiver.hpp"

#include <algorithm>
#include <cstring>

#include "dynamixel/protocol/crc16.hpp"

namespace tpf::dxl {

std::span<std::uint8_t> PacketReceiver::write_area() noexcept {
  drop_front(consumed_, false);
  consumed_ = 0;
  return std::span(buffer_).subspan(size_);
}

std::size_t PacketReceiver::feed(std::span<const std::uint8_t> bytes) noexcept {
  const auto area = write_area();
  const std::size_t n = std::min(area.size(), bytes.size());
  std::memcpy(area.data(), bytes.data(), n);
  commit(n);
  return n;
}

void PacketReceiver::drop_front(std::size_t n, bool garbage) noexcept {
  n = std::min(n, size_);
  std::memmove(buffer_.data(), buffer_.data() + n, size_ - n);
  size_ -= n;
  if (garbage) dropped_ += n;
}

bool PacketReceiver::accepts(std::uint8_t inst) const noexcept {
  const bool status = inst == static_cast<std::uint8_t>(Instruction::status);
  return accept_ == Accept::status ? status : !status;
}

RxEvent PacketReceiver::next() noexcept {
  drop_front(consumed_, false);
  consumed_ = 0;
  for (;;) {
    // Header FF FF FD xx with xx != FD (FF FF FD FD is stuffed data, not a header).
    std::size_t start = 0;
    while (start < size_) {
      const std::size_t avail = size_ - start;
      const bool ff1 = buffer_[start] == 0xFF;
      const bool ff2 = avail < 2 || buffer_[start + 1] == 0xFF;
      const bool fd = avail < 3 || buffer_[start + 2] == 0xFD;
      const bool not_stuffed = avail < 4 || buffer_[start + 3] != 0xFD;
      if (ff1 && ff2 && fd && not_stuffed) break;
      ++start;
    }
    drop_front(start, true);
    if (size_ < kHeaderBytes + 1) return RxEvent::need_more;

    const std::size_t length =
        buffer_[kOffsetLength] | (std::size_t{buffer_[kOffsetLength + 1]} << 8);
    const std::size_t min_length = accept_ == Accept::status ? 4 : 3;
    if (buffer_[kOffsetReserved] != 0x00 || length > kMaxLength || length < min_length ||
        !accepts(buffer_[kOffsetInstruction])) {
      drop_front(1, true);  // not a packet start: drop one byte and rescan
      continue;
    }
    const std::size_t total = length + kHeaderBytes;
    if (size_ < total) return RxEvent::need_more;

    const std::uint16_t crc = update_crc16(0, std::span(buffer_).first(total - 2));
    const std::uint16_t sent = buffer_[total - 2] | (std::uint16_t{buffer_[total - 1]} << 8);
    consumed_ = total;
    if (crc != sent) {
      dropped_ += total;
      return RxEvent::corrupt;
    }
    return RxEvent::packet;
  }
}

}  // namespace tpf::dxl
