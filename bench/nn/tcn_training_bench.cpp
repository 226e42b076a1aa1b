// Training time on 30 minutes of 400 Hz synthetic friction-like data (2 threads), one run.
#include <benchmark/benchmark.h>

#include <iostream>

#include "offline/compensator_training/synthetic_friction_data.hpp"
#include "offline/compensator_training/tcn_trainer.hpp"

namespace {

void BM_TcnTrain30Minutes(benchmark::State& state) {
  using namespace tpf::offline;
  TcnDataset data;
  for (int part = 0; part < 6; ++part) {  // 6 × 5 min, SYNTHETIC (see synthetic_friction_data.hpp)
    data.sequences.push_back(make_synthetic_friction_sequence(300.0, 400.0, 100 + part));
  }
  Eigen::Index samples = 0;
  double sum = 0.0, sum_sq = 0.0;
  for (const auto& s : data.sequences) {
    samples += s.residual.rows();
    sum += s.residual.sum();
    sum_sq += s.residual.squaredNorm();
  }
  const double variance = sum_sq / samples - (sum / samples) * (sum / samples);

  TcnTrainOptions options;  // per-joint default: 4 → 32 channels × 4 levels → 1, R = 46
  options.max_epochs = static_cast<int>(state.range(0));
  options.max_seconds = 300.0;
  TcnTrainResult result;
  for (auto _ : state) {
    result = train_tcn(data, options, tcn_progress_bar(std::cerr));
  }
  const TcnTrainProgress& last = result.history.back();
  state.counters["samples"] = static_cast<double>(samples);
  state.counters["epochs"] = static_cast<double>(result.history.size());
  state.counters["best_epoch"] = result.best_epoch;
  state.counters["seconds_per_epoch"] = last.elapsed_seconds / result.history.size();
  state.counters["best_val_loss"] = result.best_validation_loss;
  state.counters["residual_variance"] = variance;
  state.counters["val_loss_over_variance"] = result.best_validation_loss / variance;
}

BENCHMARK(BM_TcnTrain30Minutes)
    ->Name("TcnTrain/30min_400Hz/2threads")
    ->Arg(200)
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

}  // namespace
