// Fuzz target: any byte stream from the pad board, in fuzzer-chosen chunks, through the COBS/CRC
// PadStreamParser; plus COBS and parse_frame on the raw bytes. Contract: no overrun; delivered
// frames are well-formed (version, type, n ≤ kMaxPads) and counted; COBS decodes what it encodes.
#include <algorithm>
#include <cstring>
#include <vector>

#include "fuzz_support.hpp"
#include "teensy/host/pad_stream_parser.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace tpf::pad;
  using tpf::fuzz::violation;
  if (size < 1) return 0;
  std::size_t chunk = 1 + data[0];
  std::span<const std::uint8_t> stream(data + 1, size - 1);
  PadStreamParser parser;
  std::uint64_t delivered = 0;
  const auto on_frame = [&](const PadFrame& f) {
    ++delivered;
    if (f.version != kFrameVersion || f.type != kTypePressureKpa || f.n > kMaxPads)
      violation("PadStreamParser", "delivered a malformed frame");
  };
  while (!stream.empty()) {
    const std::size_t n = std::min(chunk, stream.size());
    parser.feed(stream.first(n), on_frame);
    stream = stream.subspan(n);
    if (data[0] & 0x80) parser.resync();
    chunk = chunk * 5 % 97 + 1;
  }
  if (delivered != parser.counters().frames) violation("PadStreamParser", "frame count differs");

  // COBS: decode never writes more than it reads; encode → decode is the identity.
  const std::vector<std::uint8_t> in(data + 1, data + size);
  std::vector<std::uint8_t> decoded(in.size());
  std::size_t decoded_size = 0;
  if (cobs_decode(in.data(), in.size(), decoded.data(), &decoded_size)) {
    if (decoded_size > in.size()) violation("cobs_decode", "wrote past its output");
  }
  std::vector<std::uint8_t> encoded(cobs_max_encoded_size(in.size()));
  const std::size_t encoded_size = cobs_encode(in.data(), in.size(), encoded.data());
  if (encoded_size > encoded.size() || std::find(encoded.begin(), encoded.begin() + encoded_size,
                                                 0) != encoded.begin() + encoded_size)
    violation("cobs_encode", "overran or emitted a zero");
  std::vector<std::uint8_t> back(encoded_size);
  if (!cobs_decode(encoded.data(), encoded_size, back.data(), &decoded_size) ||
      decoded_size != in.size() || !std::equal(in.begin(), in.end(), back.begin()))
    violation("cobs", "decode(encode(x)) != x");

  // parse_frame on an exactly-sized copy.
  PadFrame frame;
  if (parse_frame(in.data(), in.size(), frame) == FrameError::none && frame.n > kMaxPads)
    violation("parse_frame", "n > kMaxPads accepted");
  return 0;
}
