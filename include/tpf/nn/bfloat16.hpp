// bfloat16 (a float's sign, 8-bit exponent and top 7 fraction bits) for network weights that
// take half the bytes of a float: the rounding from float and the two-columns-per-word layout the
// TCN kernels read.
#pragma once

#include <bit>
#include <cstdint>
#include <initializer_list>

namespace tpf {

/// Names the evaluation of a network in float whose hidden-block weights are stored as bfloat16:
/// the NetScalar of tpf::PerJointTcn<BFloat16Weights, Hidden> (docs/tcn.md, "Precision").
struct BFloat16Weights {};

/// The bfloat16 nearest to x (ties to even), as its 16 bits; a NaN stays a (quiet) NaN, a float
/// beyond bfloat16's largest finite value rounds to ±inf as any rounding to nearest does.
constexpr std::uint16_t bfloat16_bits(float x) noexcept {
  const std::uint32_t u = std::bit_cast<std::uint32_t>(x);
  if ((u & 0x7FFFFFFFu) > 0x7F800000u) return std::uint16_t((u >> 16) | 0x0040u);
  return std::uint16_t((u + 0x7FFFu + ((u >> 16) & 1u)) >> 16);
}

/// The float of bfloat16 bits b (exact: the low 16 bits of the float are zero).
constexpr float bfloat16_value(std::uint16_t b) noexcept {
  return std::bit_cast<float>(std::uint32_t(b) << 16);
}

/// x rounded to the nearest bfloat16, as a float.
constexpr float round_to_bfloat16(float x) noexcept {
  return bfloat16_value(bfloat16_bits(x));
}

/// Two weights in one 32-bit word, read by the TCN kernels with one operation for both: the odd
/// column c + 1 is the bfloat16 in the low half (shifted up, it is that float); the even column c
/// is the whole word read as a float, its high half chosen so that this float is the one nearest
/// to the weight among those whose low half is the odd column's. Both are within half a bfloat16
/// step of their weight (2⁻⁸ of it). A type of its own, so that the kernels pick the unpacking
/// load by overload.
struct BFloat16Pair {
  std::uint32_t bits = 0;
};

/// The even column's weight a pair holds (the word read as a float).
constexpr float pair_even(BFloat16Pair p) noexcept {
  return std::bit_cast<float>(p.bits);
}
/// The odd column's weight a pair holds (the low half, shifted up).
constexpr float pair_odd(BFloat16Pair p) noexcept {
  return std::bit_cast<float>(p.bits << 16);
}

/// Whether x is zero or a normal float: the pairs hold no subnormal (on some cores a multiply by
/// one takes a slow path).
constexpr bool zero_or_normal(float x) noexcept {
  const std::uint32_t exponent = std::bit_cast<std::uint32_t>(x) & 0x7F800000u;
  return exponent != 0x7F800000u && (exponent != 0 || x == 0.0f);
}

/// The pair of the finite weights (even, odd): odd rounded to the nearest bfloat16, even to the
/// nearest float whose low half is odd's bfloat16 (of the high halves next to even's own); a
/// weight below the smallest normal float (≈ 1.2·10⁻³⁸) counts as that or 0.
constexpr BFloat16Pair bfloat16_pair(float even, float odd) noexcept {
  constexpr float smallest = 0x1p-126f;
  const std::uint32_t low = bfloat16_bits(zero_or_normal(odd) ? odd : 0.0f);
  if (!zero_or_normal(even) || (even < smallest && even > -smallest))
    even = even < 0.0f ? -smallest : smallest;
  const std::uint32_t high = std::bit_cast<std::uint32_t>(even) & 0xFFFF0000u;
  BFloat16Pair best{};
  bool found = false;
  for (const std::uint32_t other : {high - 0x10000u, high, high + 0x10000u}) {
    const BFloat16Pair candidate{(other & 0xFFFF0000u) | low};
    if (!zero_or_normal(pair_even(candidate))) continue;
    const double error = double(pair_even(candidate)) - double(even),
                 now = double(pair_even(best)) - double(even);
    if (!found || error * error < now * now) best = candidate;
    found = true;
  }
  return best;
}

}  // namespace tpf
