// The three float products of a 16-channel TCN block's training pass, in AVX2 registers when the
// CPU has them (chosen at run time; the rest of the build stays at the default x86-64 flags), and
// the ReLU's gradient mask: the training's inner loops over plain arrays, which a sanitized build
// compiles without instrumentation (src/offline/CMakeLists.txt; callers check the ranges).
#pragma once

#include <cstddef>

namespace tpf::offline {

/// True when the CPU (and the OS) support AVX2; only then may the functions below be called (on
/// other targets they are not compiled).
bool float_gemm16_available();

/// All matrices column-major and contiguous (leading dimension = rows). Every output element is
/// one sum over the inner index in increasing order, each term a multiply then an add (no fused
/// multiply-add), started at 0 and added to the previous value last, so the results equal Eigen's
/// SSE2 float GEMM (n ≥ 2; one column goes through Eigen's matrix–vector path) bit for bit
/// (FloatGemm16 tests).
///
/// B and S are read as B(i, t) = b[t·stride + offset[i]]: a stacked matrix (offset[i] = i,
/// stride = k) or, without stacking, the K lagged copies of a block input x (C_in × T):
/// offset[j·C_in + c] = (K − 1 − j)·d·C_in + c, stride = C_in (tcn_window_model).
///
/// C (16 × n) += A (16 × k) · B (k × n).
void float_gemm16_accumulate(const float* a, std::ptrdiff_t k, const float* b,
                             const std::ptrdiff_t* offset, std::ptrdiff_t stride, std::ptrdiff_t n,
                             float* c);
/// G (16 × k) = D (16 × n) · S (k × n)ᵀ; k a multiple of 4.
void float_gemm16_times_transpose(const float* d, const float* s, const std::ptrdiff_t* offset,
                                  std::ptrdiff_t stride, std::ptrdiff_t k, std::ptrdiff_t n,
                                  float* g);
/// X (k × n) = A (16 × k)ᵀ · D (16 × n), given At = Aᵀ (k × 16); k a multiple of 8.
void float_gemm16_transpose_times(const float* at, std::ptrdiff_t k, const float* d,
                                  std::ptrdiff_t n, float* x);

/// g[i] ← g[i] where y[i] > 0, else +0, for i < n (∂L/∂z = ∂L/∂y ⊙ [y > 0]; Eigen's select, bit
/// for bit), as a plain loop that the compiler turns into compare-and-mask vector code.
void relu_gradient_mask(const float* y, float* g, std::ptrdiff_t n);
void relu_gradient_mask(const double* y, double* g, std::ptrdiff_t n);

}  // namespace tpf::offline
