#include "dynamixel/protocol/byte_stuffing.hpp"

namespace tpf::dxl {
namespace {

/// True when out[k-2..k] == FF FF FD.
bool ends_with_header(std::span<const std::uint8_t> b, std::size_t k) noexcept {
  return k >= 2 && b[k] == 0xFD && b[k - 1] == 0xFF && b[k - 2] == 0xFF;
}

}  // namespace

std::size_t add_stuffing(std::span<const std::uint8_t> in, std::span<std::uint8_t> out) noexcept {
  std::size_t n = 0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (n >= out.size()) return 0;
    out[n++] = in[i];
    if (ends_with_header(in, i)) {
      if (n >= out.size()) return 0;
      out[n++] = 0xFD;
    }
  }
  return n;
}

std::size_t remove_stuffing(std::span<const std::uint8_t> in,
                            std::span<std::uint8_t> out) noexcept {
  std::size_t n = 0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    out[n++] = in[i];
    if (ends_with_header(in, i) && i + 1 < in.size() && in[i + 1] == 0xFD) ++i;  // skip the FD
  }
  return n;
}

}  // namespace tpf::dxl
