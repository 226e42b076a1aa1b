// Where the offline AVX kernels that reproduce Eigen's SSE2 summation order bit for bit
// (GramRowBlock, ThetaProducts) can run: x86-64 with GCC or clang, Eigen itself compiled for SSE2
// only (not AVX or FMA: then Eigen's own code runs), and a CPU with AVX (asked once, at run time).
#pragma once

#include <Eigen/Core>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && \
    defined(EIGEN_VECTORIZE_SSE2) && !defined(EIGEN_VECTORIZE_AVX) &&   \
    !defined(EIGEN_VECTORIZE_FMA)
#include <immintrin.h>
#define TPF_EIGEN_ORDER_AVX 1
#else
#define TPF_EIGEN_ORDER_AVX 0
#endif

namespace tpf::offline {

#if TPF_EIGEN_ORDER_AVX
/// Whether this CPU runs the kernels' AVX code.
inline bool cpu_runs_eigen_order_kernels() {
  static const bool has = __builtin_cpu_supports("avx");
  return has;
}
#endif

}  // namespace tpf::offline
