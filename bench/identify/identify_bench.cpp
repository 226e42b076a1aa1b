// Speed of closing the loop: `tpf identify` and `tpf diagnose` on a simulated log of the 4-joint
// arm with undeclared effects (data/scenarios/excitation-undeclared.json, seed 3). The counter
// s_per_log_hour is the wall time scaled to a 1-hour 400 Hz log (targets: identify ≤ 10 s,
// identify + diagnose ≤ 30 s on 2 cores). Reading the log is timed by tpf_log_bench.
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>

#include "offline/diagnose/diagnose.hpp"
#include "offline/identify/identify.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::offline {
namespace {

constexpr double kLogSeconds = 600.0;  // 10 min of log; timings scale linearly with rows

const Log& twin_log() {
  static const Log log = simulate_to_log(
      load_scenario(std::string(TPF_BENCH_DATA_DIR) + "/scenarios/excitation-undeclared.json"), 3,
      kLogSeconds);
  return log;
}

const ModelX& arm() {
  static const ModelX model =
      load_robot<double, Eigen::Dynamic>(std::string(TPF_BENCH_DATA_DIR) + "/arm4.robot.json");
  return model;
}

/// Times `run` per iteration and reports it per hour of log: wall clock (s_per_log_hour) and
/// the CPU time of every thread of the process (cpu_s_per_log_hour; the machine may be shared).
template <typename Run>
void time_per_log_hour(benchmark::State& state, Run&& run) {
  const Log& log = twin_log();
  double seconds = 0, cpu_seconds = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();  // process CPU time, all threads
    run(log);
    cpu_seconds += static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  const double per_hour = 3600.0 / (log.values(log.rows() - 1, 0) - log.values(0, 0)) /
                          static_cast<double>(state.iterations());
  state.counters["rows"] = static_cast<double>(log.rows());
  state.counters["s_per_log_hour"] = seconds * per_hour;
  state.counters["cpu_s_per_log_hour"] = cpu_seconds * per_hour;
}

void BM_Identify(benchmark::State& state) {
  time_per_log_hour(state, [](const Log& log) {
    auto id = identify(log, arm());
    benchmark::DoNotOptimize(id.nominal.base_values.data());
  });
}
BENCHMARK(BM_Identify)
    ->Unit(benchmark::kSecond)
    ->Iterations(2)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

void BM_Diagnose(benchmark::State& state) {
  time_per_log_hour(state, [](const Log& log) {
    auto d = diagnose(log, arm());
    benchmark::DoNotOptimize(d.nominal.base_values.data());
  });
}
BENCHMARK(BM_Diagnose)
    ->Unit(benchmark::kSecond)
    ->Iterations(2)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

void BM_IdentifyAndDiagnose(benchmark::State& state) {
  time_per_log_hour(state, [](const Log& log) {
    auto id = identify(log, arm());
    auto d = diagnose(log, arm());
    benchmark::DoNotOptimize(id.nominal.base_values.data());
    benchmark::DoNotOptimize(d.nominal.base_values.data());
  });
}
BENCHMARK(BM_IdentifyAndDiagnose)
    ->Unit(benchmark::kSecond)
    ->Iterations(2)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

}  // namespace
}  // namespace tpf::offline
