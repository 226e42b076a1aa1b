#include "offline/compensator_training/float_gemm16.hpp"

#if defined(__GNUC__) && defined(__x86_64__)
#include <immintrin.h>
#define TPF_FLOAT_GEMM16_AVX2 1
#endif

namespace tpf::offline {

#ifdef TPF_FLOAT_GEMM16_AVX2

// target("avx2") without "fma": the compiler cannot contract a multiply and an add into one
// rounding, so every term is rounded as in the SSE2 build.
#define TPF_AVX2 __attribute__((target("avx2")))

namespace {

/// The 16 rows of one column as two registers.
struct Column16 {
  __m256 low, high;
};

TPF_AVX2 inline Column16 zero16() {
  return {_mm256_setzero_ps(), _mm256_setzero_ps()};
}

/// acc += (a_low, a_high) · s.
TPF_AVX2 inline void add_scaled(Column16& acc, __m256 a_low, __m256 a_high, __m256 s) {
  acc.low = _mm256_add_ps(acc.low, _mm256_mul_ps(a_low, s));
  acc.high = _mm256_add_ps(acc.high, _mm256_mul_ps(a_high, s));
}

/// c[0..15] = c[0..15] + acc (the previous value first, as Eigen adds a block's sum).
TPF_AVX2 inline void add_into(float* c, const Column16& acc) {
  _mm256_storeu_ps(c, _mm256_add_ps(_mm256_loadu_ps(c), acc.low));
  _mm256_storeu_ps(c + 8, _mm256_add_ps(_mm256_loadu_ps(c + 8), acc.high));
}

/// c[0..15] = 0 + acc (0 + x turns −0 into +0, as Eigen's zero-filled destination does).
TPF_AVX2 inline void store_fresh(float* c, const Column16& acc) {
  _mm256_storeu_ps(c, _mm256_add_ps(_mm256_setzero_ps(), acc.low));
  _mm256_storeu_ps(c + 8, _mm256_add_ps(_mm256_setzero_ps(), acc.high));
}

/// Columns [t, t + 4) of C += A·B, B(i, t) = b[t·stride + offset[i]].
TPF_AVX2 void accumulate_four(const float* a, std::ptrdiff_t k, const float* b,
                              const std::ptrdiff_t* offset, std::ptrdiff_t stride, float* c) {
  Column16 c0 = zero16(), c1 = zero16(), c2 = zero16(), c3 = zero16();
  for (std::ptrdiff_t i = 0; i < k; ++i) {
    const __m256 a_low = _mm256_loadu_ps(a + 16 * i), a_high = _mm256_loadu_ps(a + 16 * i + 8);
    const float* row = b + offset[i];
    add_scaled(c0, a_low, a_high, _mm256_broadcast_ss(row));
    add_scaled(c1, a_low, a_high, _mm256_broadcast_ss(row + stride));
    add_scaled(c2, a_low, a_high, _mm256_broadcast_ss(row + 2 * stride));
    add_scaled(c3, a_low, a_high, _mm256_broadcast_ss(row + 3 * stride));
  }
  add_into(c, c0);
  add_into(c + 16, c1);
  add_into(c + 32, c2);
  add_into(c + 48, c3);
}

/// Column t of C += A·B.
TPF_AVX2 void accumulate_one(const float* a, std::ptrdiff_t k, const float* b,
                             const std::ptrdiff_t* offset, float* c) {
  Column16 acc = zero16();
  for (std::ptrdiff_t i = 0; i < k; ++i)
    add_scaled(acc, _mm256_loadu_ps(a + 16 * i), _mm256_loadu_ps(a + 16 * i + 8),
               _mm256_broadcast_ss(b + offset[i]));
  add_into(c, acc);
}

/// Rows [r, r + 8·blocks) of columns [t, t + columns) of X = Aᵀ·D, blocks ≤ 4, columns ≤ 2.
template <int blocks, int columns>
TPF_AVX2 inline void transpose_times_tile(const float* at, std::ptrdiff_t k, const float* d,
                                          std::ptrdiff_t r, std::ptrdiff_t t, float* x) {
  __m256 acc[columns][blocks];
  for (int c = 0; c < columns; ++c)
    for (int b = 0; b < blocks; ++b)
      acc[c][b] = _mm256_setzero_ps();
  for (int i = 0; i < 16; ++i) {
    __m256 scale[columns];
    for (int c = 0; c < columns; ++c)
      scale[c] = _mm256_broadcast_ss(d + 16 * (t + c) + i);
    for (int b = 0; b < blocks; ++b) {
      const __m256 a = _mm256_loadu_ps(at + i * k + r + 8 * b);
      for (int c = 0; c < columns; ++c)
        acc[c][b] = _mm256_add_ps(acc[c][b], _mm256_mul_ps(a, scale[c]));
    }
  }
  for (int c = 0; c < columns; ++c)
    for (int b = 0; b < blocks; ++b)
      _mm256_storeu_ps(x + (t + c) * k + r + 8 * b, _mm256_add_ps(_mm256_setzero_ps(), acc[c][b]));
}

/// Columns [t, t + columns) of X = Aᵀ·D.
template <int columns>
TPF_AVX2 inline void transpose_times_columns(const float* at, std::ptrdiff_t k, const float* d,
                                             std::ptrdiff_t t, float* x) {
  std::ptrdiff_t r = 0;
  for (; r + 32 <= k; r += 32)
    transpose_times_tile<4, columns>(at, k, d, r, t, x);
  for (; r < k; r += 8)
    transpose_times_tile<1, columns>(at, k, d, r, t, x);
}

}  // namespace

TPF_AVX2 void float_gemm16_accumulate(const float* a, std::ptrdiff_t k, const float* b,
                                      const std::ptrdiff_t* offset, std::ptrdiff_t stride,
                                      std::ptrdiff_t n, float* c) {
  std::ptrdiff_t t = 0;
  for (; t + 4 <= n; t += 4)
    accumulate_four(a, k, b + t * stride, offset, stride, c + 16 * t);
  for (; t < n; ++t)
    accumulate_one(a, k, b + t * stride, offset, c + 16 * t);
}

TPF_AVX2 void float_gemm16_times_transpose(const float* d, const float* s,
                                           const std::ptrdiff_t* offset, std::ptrdiff_t stride,
                                           std::ptrdiff_t k, std::ptrdiff_t n, float* g) {
  for (std::ptrdiff_t j = 0; j < k; j += 4) {
    Column16 g0 = zero16(), g1 = zero16(), g2 = zero16(), g3 = zero16();
    const std::ptrdiff_t o0 = offset[j], o1 = offset[j + 1], o2 = offset[j + 2], o3 = offset[j + 3];
    for (std::ptrdiff_t t = 0; t < n; ++t) {
      const __m256 d_low = _mm256_loadu_ps(d + 16 * t), d_high = _mm256_loadu_ps(d + 16 * t + 8);
      const float* column = s + t * stride;
      add_scaled(g0, d_low, d_high, _mm256_broadcast_ss(column + o0));
      add_scaled(g1, d_low, d_high, _mm256_broadcast_ss(column + o1));
      add_scaled(g2, d_low, d_high, _mm256_broadcast_ss(column + o2));
      add_scaled(g3, d_low, d_high, _mm256_broadcast_ss(column + o3));
    }
    store_fresh(g + 16 * j, g0);
    store_fresh(g + 16 * (j + 1), g1);
    store_fresh(g + 16 * (j + 2), g2);
    store_fresh(g + 16 * (j + 3), g3);
  }
}

TPF_AVX2 void float_gemm16_transpose_times(const float* at, std::ptrdiff_t k, const float* d,
                                           std::ptrdiff_t n, float* x) {
  std::ptrdiff_t t = 0;
  for (; t + 2 <= n; t += 2)
    transpose_times_columns<2>(at, k, d, t, x);
  for (; t < n; ++t)
    transpose_times_columns<1>(at, k, d, t, x);
}

bool float_gemm16_available() {
  static const bool available = __builtin_cpu_supports("avx2");
  return available;
}

#undef TPF_AVX2

#else

bool float_gemm16_available() {
  return false;
}

#endif

namespace {

template <typename S>
void mask_by_positive(const S* __restrict y, S* __restrict g, std::ptrdiff_t n) {
  for (std::ptrdiff_t i = 0; i < n; ++i)
    g[i] = y[i] > S(0) ? g[i] : S(0);
}

}  // namespace

void relu_gradient_mask(const float* y, float* g, std::ptrdiff_t n) {
  mask_by_positive(y, g, n);
}

void relu_gradient_mask(const double* y, double* g, std::ptrdiff_t n) {
  mask_by_positive(y, g, n);
}

}  // namespace tpf::offline

#undef TPF_FLOAT_GEMM16_AVX2  // file-local (unity builds)
