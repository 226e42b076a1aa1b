// Speed of the digital twin: simulated seconds of the default excitation per wall second.
// Target: 10 minutes of simulated log in ≤ 20 s on one core.
//   cmake --build --preset release --target tpf_sim_bench && build/release/bin/tpf_sim_bench
#include <benchmark/benchmark.h>

#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"

namespace {

void BM_SimulateExcitation(benchmark::State& state) {
  const auto scenario =
      tpf::offline::load_scenario(TPF_BENCH_DATA_DIR "/scenarios/excitation.json");
  const double duration = static_cast<double>(state.range(0));
  std::size_t rows = 0;
  for (auto _ : state) {
    double checksum = 0.0;
    const auto summary = tpf::offline::simulate(
        scenario, 1, duration, [&](std::span<const double> row) { checksum += row[9]; });
    rows += summary.rows;
    benchmark::DoNotOptimize(checksum);
  }
  state.counters["sim_s_per_wall_s"] = benchmark::Counter(
      duration * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["rows"] = static_cast<double>(rows) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_SimulateExcitation)->Arg(60)->Unit(benchmark::kSecond)->Iterations(3);

}  // namespace
