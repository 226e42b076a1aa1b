// Rounding to bfloat16 against an independent reference (the nearer of the two bfloat16 values
// that bracket x, computed in double), and the pair layout the TCN kernels unpack.
#include "tpf/nn/bfloat16.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace tpf {
namespace {

/// The bfloat16 nearest to finite x, ties to the even one, from the two candidates that bracket
/// it (x with its low 16 bits cleared, and the next bfloat16 away from zero).
std::uint16_t nearest_bfloat16_reference(float x) {
  const std::uint32_t u = std::bit_cast<std::uint32_t>(x);
  const std::uint32_t toward_zero = u & 0xFFFF0000u, away = toward_zero + 0x10000u;
  const double low = std::bit_cast<float>(toward_zero);
  // The candidate away from zero may be ±inf (x beyond the largest bfloat16): its distance is
  // then that of the next power of two, 2^128.
  const double high = (away & 0x7FFFFFFFu) == 0x7F800000u
                          ? std::copysign(std::ldexp(1.0, 128), double(x))
                          : double(std::bit_cast<float>(away));
  const double below = std::abs(double(x) - low), above = std::abs(high - double(x));
  if (below < above) return std::uint16_t(toward_zero >> 16);
  if (above < below) return std::uint16_t(away >> 16);
  return std::uint16_t(((toward_zero >> 16) & 1u) == 0 ? toward_zero >> 16 : away >> 16);
}

TEST(BFloat16, RoundsKnownValues) {
  EXPECT_EQ(bfloat16_bits(1.0f), 0x3F80);
  EXPECT_EQ(bfloat16_bits(-2.5f), 0xC020);
  EXPECT_EQ(bfloat16_bits(1.0f + 0x1p-8f), 0x3F80);             // half way: to the even 1
  EXPECT_EQ(bfloat16_bits(1.0f + 3 * 0x1p-8f), 0x3F82);         // half way: to the even 1 + 2^-6
  EXPECT_EQ(bfloat16_bits(1.0f + 0x1p-8f + 0x1p-20f), 0x3F81);  // just above half way: up
  EXPECT_EQ(bfloat16_value(bfloat16_bits(0.1f)), 0.10009765625f);
  EXPECT_EQ(bfloat16_bits(std::numeric_limits<float>::max()), 0x7F80);  // beyond: +inf
  EXPECT_EQ(bfloat16_bits(-std::numeric_limits<float>::infinity()), 0xFF80);
  EXPECT_TRUE(std::isnan(round_to_bfloat16(std::numeric_limits<float>::quiet_NaN())));
  // A NaN whose payload lies only in the low 16 bits stays a NaN (not ±inf).
  EXPECT_TRUE(std::isnan(round_to_bfloat16(std::bit_cast<float>(0x7F800001u))));
  EXPECT_EQ(std::bit_cast<std::uint32_t>(round_to_bfloat16(-0.0f)), 0x80000000u);
}

TEST(BFloat16, RoundsToTheNearestLikeTheReference) {
  std::mt19937 rng(7);
  int checked = 0;
  for (int i = 0; i < 200000; ++i) {
    std::uint32_t u = rng();
    if (i % 4 == 0) u = (u & 0xFFFF0000u) | 0x8000u;  // every fourth a tie
    const float x = std::bit_cast<float>(u);
    if (!std::isfinite(x)) continue;
    ASSERT_EQ(bfloat16_bits(x), nearest_bfloat16_reference(x)) << std::hexfloat << x;
    ++checked;
  }
  EXPECT_GT(checked, 190000);
}

/// The float nearest to `even` among the 65 536 whose low half is `low` (zero or normal ones),
/// by search.
float nearest_with_low_half(float even, std::uint32_t low) {
  float best = std::numeric_limits<float>::quiet_NaN();
  for (std::uint32_t high = 0; high < 0x10000u; ++high) {
    const float value = std::bit_cast<float>((high << 16) | low);
    if (!std::isfinite(value) || (value != 0.0f && std::abs(value) < 0x1p-126f)) continue;
    if (std::isnan(best) || std::abs(double(value) - even) < std::abs(double(best) - even))
      best = value;
  }
  return best;
}

// The pair: the odd weight is its nearest bfloat16 (the low half shifted up), the even one the
// word itself, the float nearest to it among those with that low half (a search over all 2^16
// high halves), so within half a bfloat16 step (2^-8 relative) of the weight.
TEST(BFloat16, PairHoldsTheOddWeightLowAndTheNearestEvenWeightAroundIt) {
  const BFloat16Pair p = bfloat16_pair(1.0f, -2.5f);
  EXPECT_EQ(p.bits & 0xFFFFu, 0xC020u);
  EXPECT_EQ(pair_odd(p), -2.5f);
  std::mt19937 rng(11);
  std::normal_distribution<float> weight(0.0f, 0.3f);
  for (int i = 0; i < 200; ++i) {
    const float even = i == 0 ? 0.0f : weight(rng), odd = i == 1 ? 0.0f : weight(rng);
    const BFloat16Pair pair = bfloat16_pair(even, odd);
    ASSERT_EQ(pair_odd(pair), round_to_bfloat16(odd)) << odd;
    ASSERT_EQ(pair_even(pair), nearest_with_low_half(even, bfloat16_bits(odd)))
        << std::hexfloat << even << " " << odd;
    EXPECT_LE(std::abs(pair_even(pair) - even), 0x1p-8f * std::abs(even) + 0x1p-125f) << even;
  }
  // Weights too small for a normal float: no subnormal in the pair.
  const BFloat16Pair tiny = bfloat16_pair(1e-40f, -1e-40f);
  EXPECT_EQ(pair_odd(tiny), 0.0f);
  EXPECT_GE(std::abs(pair_even(tiny)), 0x1p-126f);
  EXPECT_LE(std::abs(pair_even(tiny)), 0x1p-125f);
}

}  // namespace
}  // namespace tpf
