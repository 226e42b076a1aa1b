// The machine's bound on a TCN step whose weights do not fit the L1 cache: 64-byte loads
// streaming one network's worth of weights, from L1 (the 16-channel float network) and from L2
// (the 32-channel double one), the bytes a second reported. No arithmetic but one add per load,
// and aligned loads: the fastest these bytes can be read here.
#include <benchmark/benchmark.h>

#include <memory>

#include "tpf/nn/tcn.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>

namespace {

/// Sums `bytes` (a multiple of 512) of `data` in 64-byte loads, 8 independent sums.
__attribute__((target("avx512f"))) double stream_sum(const double* data, std::size_t bytes) {
  __m512d sum[8];
  for (__m512d& s : sum)
    s = _mm512_setzero_pd();
  const std::size_t vectors = bytes / 64;
  for (std::size_t v = 0; v < vectors; v += 8)
    for (int k = 0; k < 8; ++k)
      sum[k] = _mm512_add_pd(sum[k], _mm512_loadu_pd(data + 8 * (v + k)));
  for (int k = 1; k < 8; ++k)
    sum[0] = _mm512_add_pd(sum[0], sum[k]);
  alignas(64) double lanes[8];
  _mm512_store_pd(lanes, sum[0]);
  return lanes[0] + lanes[1] + lanes[2] + lanes[3] + lanes[4] + lanes[5] + lanes[6] + lanes[7];
}

/// Streams a buffer of sizeof(Weights) bytes (rounded down to 512) once per iteration.
template <typename Weights>
void BM_WeightStream(benchmark::State& state) {
  if (!tpf::tcn_kernel_supported(tpf::TcnKernel::Avx512)) {
    state.SkipWithError("no AVX-512 here");
    return;
  }
  const std::size_t bytes = sizeof(Weights) / 512 * 512;
  struct alignas(64) CacheLine {  // 64-byte aligned: no load spans two lines (the best case)
    double values[8];
  };
  auto lines = std::make_unique<CacheLine[]>(bytes / 64);
  double* data = lines[0].values;
  for (std::size_t i = 0; i < bytes / sizeof(double); ++i)
    data[i] = 1e-3 * double(i % 7);
  for (auto _ : state)
    benchmark::DoNotOptimize(stream_sum(data, bytes));
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * bytes));
  state.counters["kB"] = double(bytes) / 1024;
}

BENCHMARK(BM_WeightStream<tpf::TcnWeights<float, 4, 16, 4, 4, 1>>)->Name("WeightStream/float/16ch");
BENCHMARK(BM_WeightStream<tpf::TcnWeights<double, 4, 32, 4, 4, 1>>)
    ->Name("WeightStream/double/32ch");

}  // namespace

#endif
