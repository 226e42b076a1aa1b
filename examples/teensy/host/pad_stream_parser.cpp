#include "teensy/host/pad_stream_parser.hpp"

namespace tpf::pad {

void PadStreamParser::resync() noexcept {
  size_ = 0;
  synced_ = false;
  overlong_ = false;
  have_seq_ = false;
}

bool PadStreamParser::push(std::uint8_t b) noexcept {
  if (!synced_) {  // start-up garbage: wait for the first delimiter
    if (b == 0x00)
      synced_ = true;
    else
      ++counters_.startup_bytes;
    return false;
  }
  if (b != 0x00) {
    if (size_ < encoded_.size()) {
      encoded_[size_++] = b;
    } else if (!overlong_) {
      overlong_ = true;  // dropped as a whole at the next delimiter
      ++counters_.overlong;
    }
    return false;
  }
  const bool ok = !overlong_ && finish_frame();
  size_ = 0;
  overlong_ = false;
  return ok;
}

bool PadStreamParser::finish_frame() noexcept {
  if (size_ == 0) {
    ++counters_.empty_frames;
    return false;
  }
  std::uint8_t raw[kMaxWireBytes];
  std::size_t raw_size = 0;
  if (!cobs_decode(encoded_.data(), size_, raw, &raw_size)) {
    ++counters_.cobs_errors;
    return false;
  }
  switch (parse_frame(raw, raw_size, frame_)) {
    case FrameError::none:
      break;
    case FrameError::crc:
      ++counters_.crc_errors;
      return false;
    default:
      ++counters_.format_errors;
      return false;
  }
  if (have_seq_) {
    const auto gap = static_cast<std::uint16_t>(frame_.seq - last_seq_ - 1);  // modulo 2^16
    counters_.lost_frames += gap;
  }
  have_seq_ = true;
  last_seq_ = frame_.seq;
  ++counters_.frames;
  return true;
}

}  // namespace tpf::pad
