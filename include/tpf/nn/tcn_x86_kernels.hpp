// The TCN step in AVX2 + FMA or AVX-512 registers, chosen at run time on x86-64 (GCC, clang).
#pragma once

#include <array>
#include <type_traits>

#include "tpf/nn/bfloat16.hpp"
#include "tpf/nn/tcn_architecture.hpp"
#include "tpf/nn/tcn_weights.hpp"

// On x86-64 (GCC, clang) the step runs in the widest registers the CPU has, whatever the
// translation unit's flags (TPF_NATIVE=ON included).
#if (defined(__GNUC__) || defined(__clang__)) && defined(__x86_64__)
#define TPF_TCN_DISPATCH 1
#include <immintrin.h>
#endif

namespace tpf {

/// How Tcn::step computes: the compile-time path (Eigen at the translation unit's flags), or one
/// of the kernels below in wider registers than the build's.
enum class TcnKernel { Portable, Avx2, Avx512 };

/// Whether this build has the x86 kernels and this CPU (and its OS) runs `kernel`.
inline bool tcn_kernel_supported(TcnKernel kernel) noexcept {
#ifdef TPF_TCN_DISPATCH
  __builtin_cpu_init();  // also valid before main (a Tcn in a static object)
  switch (kernel) {
    case TcnKernel::Portable:
      return true;
    case TcnKernel::Avx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    case TcnKernel::Avx512:
      return __builtin_cpu_supports("avx512f");
  }
  return false;
#else
  return kernel == TcnKernel::Portable;
#endif
}

/// Whether `kernel` computes Tcn<S, ·, Hidden, …>: a float or double hidden vector that fills
/// whole registers (32 bytes AVX2, 64 bytes AVX-512; e.g. 16 floats, 32 doubles).
template <typename S, int Hidden>
constexpr bool tcn_kernel_fits(TcnKernel kernel) noexcept {
  if (!std::is_same_v<S, float> && !std::is_same_v<S, double>) return false;
  const int bytes = Hidden * int(sizeof(S));
  switch (kernel) {
    case TcnKernel::Portable:
      return true;
    case TcnKernel::Avx2:
      return bytes % 32 == 0;
    case TcnKernel::Avx512:
      return bytes % 64 == 0;
  }
  return false;
}

/// The kernel a new Tcn<S, ·, Hidden, …> uses: the widest that fits and this CPU runs, found
/// once (the first call; a Tcn's constructor makes it, before any real-time loop) and cached.
template <typename S, int Hidden>
TcnKernel preferred_tcn_kernel() noexcept {
  static const TcnKernel chosen = [] {
    for (TcnKernel k : {TcnKernel::Avx512, TcnKernel::Avx2})
      if (tcn_kernel_fits<S, Hidden>(k) && tcn_kernel_supported(k)) return k;
    return TcnKernel::Portable;
  }();
  return chosen;
}

/// What a kernel reads and writes of a Tcn's state for one step. The ring heads are those before
/// the step: x(t) is already in column input_head of the input ring; block l ≥ 1 writes its input
/// to column heads[l] of its ring. Nothing needs any alignment.
template <typename S>
struct TcnStepBuffers {
  const S* input_history;  ///< In × Kernel, column-major
  int input_head;
  S* hidden_history;  ///< rings of blocks 1 … Levels−1, back to back (Tcn::hidden_history_)
  const int* heads;   ///< Levels entries
  /// Every block's pending sums, back to back (Tcn::pending_, TcnShape::pending_offsets): slot
  /// (heads[l] + m) mod ((K − 1)·d_l + 1) of block l holds Σ_{j ≥ 1, j·d_l ≥ m} W_{l,j}·h_{l−1}(t
  /// + m − j·d_l), the lagged taps' part of z_l(t + m) that is known before t + m (heads[0] =
  /// input_head for block 0).
  S* pending;
  S* hidden;  ///< out: h_{L−1}(t), Hidden
  S* low;     ///< out (Out == 1): low(t) = c_low + A_low·h_{L−1}(t)
  S* high;    ///< out (Out == 1): high(t)
};

#ifdef TPF_TCN_DISPATCH

namespace tcn_x86 {

/// i mod n for i in [0, 2n), without a branch.
constexpr int wrap(int i, int n) noexcept {
  return i - n * int(i >= n);
}

/// Registers of a hidden vector (V in all) that one pass over a block's columns keeps in
/// accumulators: the largest divisor R of V whose (current_sums(R) + K − 1)·R accumulators leave
/// 4 of the width's `registers` free.
constexpr int current_sums(int rows) noexcept {
  return rows >= 4 ? 1 : 4 / rows;
}
constexpr int lagged_sums(int rows, int K) noexcept {
  return (K - 1) * rows >= 6 ? 1 : 2;
}
constexpr int row_registers(int V, int K, int registers) noexcept {
  for (int rows = V; rows > 1; --rows)
    if (V % rows == 0 && (current_sums(rows) + K - 1) * rows <= registers - 4) return rows;
  return 1;
}

/// Columns of a tap that one load of its weights holds: 1 in S, 2 in bfloat16 pairs.
template <typename Tap>
constexpr int columns_per_load() noexcept {
  return std::is_same_v<Tap, BFloat16Pair> ? 2 : 1;
}

/// One block's operands in a step: its taps W_0 … W_{K−1} (Hidden × columns each, column-major:
/// Tap = S, or two columns a word: Tap = BFloat16Pair), its input x(t) and its pending sums for
/// t, t + d, …, t + (K − 1)·d (TcnStepBuffers::pending).
template <typename Tap, typename S, int K>
struct BlockStep {
  const Tap* taps[K];
  const S* x;
  S* pending[K];
};

#define TPF_TCN_AVX2 __attribute__((target("avx2,fma"), always_inline)) inline
#define TPF_TCN_AVX512 __attribute__((target("avx512f"), always_inline)) inline

// The kernel body unrolls its register loops for speed (`TPF_TCN_UNROLL(n)`: GCC's and clang's
// `#pragma GCC unroll n`). Under AddressSanitizer (the CI build) the loops stay rolled: the same
// operations in the same order, and the test targets that step many shapes compile in about half
// the time (the unrolled bodies, each load instrumented, doubled the TCN tests' compile time).
#if defined(__SANITIZE_ADDRESS__)
#define TPF_TCN_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define TPF_TCN_SANITIZED 1
#endif
#endif
#if defined(TPF_TCN_SANITIZED)
#define TPF_TCN_UNROLL(n)
#else
#define TPF_TCN_PRAGMA(text) _Pragma(#text)
#define TPF_TCN_UNROLL(n) TPF_TCN_PRAGMA(GCC unroll n)
#endif

// The same few operations on each register type, overloaded by scalar (load, broadcast) or
// register type: unaligned load and store, broadcast from memory or of one lane, fused
// multiply-add, add, max with 0 and the sum of the lanes.
TPF_TCN_AVX2 __m256 load256(const float* p) {
  return _mm256_loadu_ps(p);
}
TPF_TCN_AVX2 __m256d load256(const double* p) {
  return _mm256_loadu_pd(p);
}
TPF_TCN_AVX2 __m256 splat256(const float* p) {
  return _mm256_broadcast_ss(p);
}
TPF_TCN_AVX2 __m256d splat256(const double* p) {
  return _mm256_broadcast_sd(p);
}
TPF_TCN_AVX2 __m256 splat_lane(__m256 a, int lane) {
  return _mm256_permutevar8x32_ps(a, _mm256_set1_epi32(lane));
}
TPF_TCN_AVX2 __m256d splat_lane(__m256d a, int lane) {
  return _mm256_castps_pd(_mm256_permutevar8x32_ps(
      _mm256_castpd_ps(a), _mm256_setr_epi32(2 * lane, 2 * lane + 1, 2 * lane, 2 * lane + 1,
                                             2 * lane, 2 * lane + 1, 2 * lane, 2 * lane + 1)));
}
TPF_TCN_AVX2 void store(float* p, __m256 v) {
  _mm256_storeu_ps(p, v);
}
TPF_TCN_AVX2 void store(double* p, __m256d v) {
  _mm256_storeu_pd(p, v);
}
TPF_TCN_AVX2 __m256 fmadd(__m256 a, __m256 b, __m256 c) {
  return _mm256_fmadd_ps(a, b, c);
}
TPF_TCN_AVX2 __m256d fmadd(__m256d a, __m256d b, __m256d c) {
  return _mm256_fmadd_pd(a, b, c);
}
TPF_TCN_AVX2 __m256 add(__m256 a, __m256 b) {
  return _mm256_add_ps(a, b);
}
TPF_TCN_AVX2 __m256d add(__m256d a, __m256d b) {
  return _mm256_add_pd(a, b);
}
TPF_TCN_AVX2 __m256 relu(__m256 a) {
  return _mm256_max_ps(a, _mm256_setzero_ps());
}
TPF_TCN_AVX2 __m256d relu(__m256d a) {
  return _mm256_max_pd(a, _mm256_setzero_pd());
}
/// Rows [offset, offset + width) of the columns from c on that one load holds
/// (columns_per_load) of a Hidden-row tap: one column in S, or two from bfloat16 pairs (c even:
/// the even column is the words themselves, the odd one their low halves shifted up;
/// bfloat16.hpp). The pairs' load is made opaque, so that the compiler loads them once for both
/// columns rather than folding the load into each.
template <int Hidden>
TPF_TCN_AVX2 void weights256(const float* tap, int c, int offset, __m256 (&w)[1]) {
  w[0] = load256(tap + c * Hidden + offset);
}
template <int Hidden>
TPF_TCN_AVX2 void weights256(const double* tap, int c, int offset, __m256d (&w)[1]) {
  w[0] = load256(tap + c * Hidden + offset);
}
template <int Hidden>
TPF_TCN_AVX2 void weights256(const BFloat16Pair* tap, int c, int offset, __m256 (&w)[2]) {
  __m256i pair =
      _mm256_loadu_si256(reinterpret_cast<const __m256i*>(tap + (c / 2) * Hidden + offset));
  asm("" : "+x"(pair));
  w[0] = _mm256_castsi256_ps(pair);
  w[1] = _mm256_castsi256_ps(_mm256_slli_epi32(pair, 16));
}
TPF_TCN_AVX2 float lane_sum(__m256 a) {
  __m128 s = _mm_add_ps(_mm256_castps256_ps128(a), _mm256_extractf128_ps(a, 1));
  s = _mm_add_ps(s, _mm_movehl_ps(s, s));
  return _mm_cvtss_f32(_mm_add_ss(s, _mm_movehdup_ps(s)));
}
TPF_TCN_AVX2 double lane_sum(__m256d a) {
  __m128d s = _mm_add_pd(_mm256_castpd256_pd128(a), _mm256_extractf128_pd(a, 1));
  return _mm_cvtsd_f64(_mm_add_sd(s, _mm_unpackhi_pd(s, s)));
}

TPF_TCN_AVX512 __m512 load512(const float* p) {
  return _mm512_loadu_ps(p);
}
TPF_TCN_AVX512 __m512d load512(const double* p) {
  return _mm512_loadu_pd(p);
}
TPF_TCN_AVX512 __m512 splat512(const float* p) {
  return _mm512_set1_ps(*p);
}
TPF_TCN_AVX512 __m512d splat512(const double* p) {
  return _mm512_set1_pd(*p);
}
// (Zero-masking forms: GCC 12 warns of the unmasked forms' undefined pass-through operand.)
TPF_TCN_AVX512 __m512 splat_lane(__m512 a, int lane) {
  return _mm512_maskz_permutexvar_ps(__mmask16(0xFFFF), _mm512_set1_epi32(lane), a);
}
TPF_TCN_AVX512 __m512d splat_lane(__m512d a, int lane) {
  return _mm512_maskz_permutexvar_pd(__mmask8(0xFF), _mm512_set1_epi64(lane), a);
}
TPF_TCN_AVX512 void store(float* p, __m512 v) {
  _mm512_storeu_ps(p, v);
}
TPF_TCN_AVX512 void store(double* p, __m512d v) {
  _mm512_storeu_pd(p, v);
}
TPF_TCN_AVX512 __m512 fmadd(__m512 a, __m512 b, __m512 c) {
  return _mm512_fmadd_ps(a, b, c);
}
TPF_TCN_AVX512 __m512d fmadd(__m512d a, __m512d b, __m512d c) {
  return _mm512_fmadd_pd(a, b, c);
}
TPF_TCN_AVX512 __m512 add(__m512 a, __m512 b) {
  return _mm512_add_ps(a, b);
}
TPF_TCN_AVX512 __m512d add(__m512d a, __m512d b) {
  return _mm512_add_pd(a, b);
}
TPF_TCN_AVX512 __m512 relu(__m512 a) {
  return _mm512_maskz_max_ps(__mmask16(0xFFFF), a, _mm512_setzero_ps());
}
TPF_TCN_AVX512 __m512d relu(__m512d a) {
  return _mm512_maskz_max_pd(__mmask8(0xFF), a, _mm512_setzero_pd());
}
template <int Hidden>
TPF_TCN_AVX512 void weights512(const float* tap, int c, int offset, __m512 (&w)[1]) {
  w[0] = load512(tap + c * Hidden + offset);
}
template <int Hidden>
TPF_TCN_AVX512 void weights512(const double* tap, int c, int offset, __m512d (&w)[1]) {
  w[0] = load512(tap + c * Hidden + offset);
}
template <int Hidden>
TPF_TCN_AVX512 void weights512(const BFloat16Pair* tap, int c, int offset, __m512 (&w)[2]) {
  __m512i pair = _mm512_loadu_si512(tap + (c / 2) * Hidden + offset);
  asm("" : "+v"(pair));
  w[0] = _mm512_castsi512_ps(pair);
  w[1] = _mm512_castsi512_ps(_mm512_maskz_slli_epi32(__mmask16(0xFFFF), pair, 16));
}
// (GCC 12's unmasked extracts and 512 → 256 casts leave a lane undefined and warn.)
template <int Half>
TPF_TCN_AVX512 __m256d half(__m512d a) {
  return _mm512_maskz_extractf64x4_pd(__mmask8(0xF), a, Half);
}
TPF_TCN_AVX512 float lane_sum(__m512 a) {
  const __m512d d = _mm512_castps_pd(a);
  const __m256 s8 = _mm256_add_ps(_mm256_castpd_ps(half<0>(d)), _mm256_castpd_ps(half<1>(d)));
  __m128 s = _mm_add_ps(_mm256_castps256_ps128(s8), _mm256_extractf128_ps(s8, 1));
  s = _mm_add_ps(s, _mm_movehl_ps(s, s));
  return _mm_cvtss_f32(_mm_add_ss(s, _mm_movehdup_ps(s)));
}
TPF_TCN_AVX512 double lane_sum(__m512d a) {
  const __m256d s4 = _mm256_add_pd(half<0>(a), half<1>(a));
  const __m128d s = _mm_add_pd(_mm256_castpd256_pd128(s4), _mm256_extractf128_pd(s4, 1));
  return _mm_cvtsd_f64(_mm_add_sd(s, _mm_unpackhi_pd(s, s)));
}

// The step, once per register width: tcn_x86_step_body.hpp, included below for each. A hidden
// vector is V registers, taken R at a time (row_registers). Each block splits its taps by when
// their sum is needed:
//   now    z = (bias + skip + pending(t)) + W_0·x(t) (+ P·x(t), block 0's projection), the axpys
//          dealt by column to A sums (A·R ≥ 4 chains): the critical path from block to block;
//   later  pending(t + j·d) += W_j·x(t) for 1 ≤ j < K, K − 1 taps on one broadcast of each x_c,
//          each dealt to B sums ((K − 1)·R·B ≥ 6 chains); its slot t + (K − 1)·d starts at zero.
// Every x_c is broadcast once for `now` and once for `later` instead of once per tap. In AVX-512
// the lagged taps' broadcasts are lane permutes of the registers that hold x (only block 0's raw
// input is loaded from memory): a step's 64-byte weight loads keep the load ports busy, a permute
// runs beside the FMAs. In AVX2 they are loads from the ring column: 16 registers cannot also
// keep the eight lane indices, so each permute first builds or loads its index; loaded, the
// 16-channel float step took 119–121 against 141–146 ns on a Zen 3 core (docs/performance.md).
// `later` of block l comes after `now` of block l + 1 in the instruction stream, so the vector unit
// fills the waits of the critical path with it. The sum of the lagged taps thus runs from
// the oldest tap to the newest, one FMA at a time; the order differs from the portable path's
// and each multiply-add rounds once: equal to rounding (tests/nn/tcn_kernel_test.cpp). Weights,
// rings, pending sums and outputs are read and written unaligned.

#define TPF_TCN_INLINE TPF_TCN_AVX2
#define TPF_TCN_TARGET "avx2,fma"
#define TPF_TCN_BYTES 32
#define TPF_TCN_LOAD load256
#define TPF_TCN_WEIGHTS weights256
#define TPF_TCN_LANE_BROADCAST 0
#define TPF_TCN_SPLAT splat256
#define TPF_TCN_REGISTERS 16
#define TPF_TCN_SUM sum256
#define TPF_TCN_NOW now256
#define TPF_TCN_LATER later256
#define TPF_TCN_LATER_ALL later_all256
#define TPF_TCN_STEP step_avx2
#include "tpf/nn/tcn_x86_step_body.hpp"

#define TPF_TCN_INLINE TPF_TCN_AVX512
#define TPF_TCN_TARGET "avx512f"
#define TPF_TCN_BYTES 64
#define TPF_TCN_LOAD load512
#define TPF_TCN_WEIGHTS weights512
#define TPF_TCN_LANE_BROADCAST 1
#define TPF_TCN_SPLAT splat512
#define TPF_TCN_REGISTERS 32
#define TPF_TCN_SUM sum512
#define TPF_TCN_NOW now512
#define TPF_TCN_LATER later512
#define TPF_TCN_LATER_ALL later_all512
#define TPF_TCN_STEP step_avx512
#include "tpf/nn/tcn_x86_step_body.hpp"

#undef TPF_TCN_AVX2
#undef TPF_TCN_AVX512
#undef TPF_TCN_UNROLL
#undef TPF_TCN_PRAGMA
#undef TPF_TCN_SANITIZED

}  // namespace tcn_x86

#endif  // TPF_TCN_DISPATCH

}  // namespace tpf
