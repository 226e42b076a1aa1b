// Read and write speed of a 1-hour 400 Hz log: 1.44 M rows, 4 joints, 8 pads, 30 columns with
// values quantised as the hardware reports them (docs/log-format-notes.md lists the figures).
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "offline/log/log_writer.hpp"
#include "offline/log/read_log.hpp"

namespace tpf::offline {
namespace {

constexpr Eigen::Index kRows = 1'440'000;  // 3600 s × 400 Hz

/// A seeded log shaped like a recording from the arm.
Log hour_log() {
  Log log;
  log.meta.set("robot", "arm4");
  log.meta.set("rate_hz", "400");
  for (const char* name : {"t"})
    log.columns.emplace_back(name);
  for (const char* prefix : {"q", "dq", "i", "temp", "vin"})
    for (int j = 1; j <= 4; ++j)
      log.columns.push_back(indexed_name(prefix, j));
  for (int k = 1; k <= 8; ++k)
    log.columns.push_back(indexed_name("p", k));
  log.columns.emplace_back("gt_contact");
  log.values.resize(kRows, static_cast<Eigen::Index>(log.columns.size()));
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (Eigen::Index r = 0; r < kRows; ++r) {
    const double t = static_cast<double>(r) / 400.0;
    log.values(r, 0) = t;
    for (int j = 0; j < 4; ++j) {
      const double phase = 0.3 * t * (j + 1);
      log.values(r, 1 + j) = std::round(1e5 * std::sin(phase)) * 6.259113e-6;   // pulses → rad
      log.values(r, 5 + j) = std::round(300 * std::cos(phase)) * 1.0471976e-3;  // 0.01 rpm → rad/s
      log.values(r, 9 + j) = std::round(200 * std::sin(phase) + 20 * noise(rng));  // mA
      log.values(r, 13 + j) = 35 + (r / 4000) % 5;                                 // °C
      log.values(r, 17 + j) = std::round(240 + noise(rng)) / 10;                   // V
    }
    for (int k = 0; k < 8; ++k)
      log.values(r, 21 + k) = std::round(1000 * noise(rng)) / 1000;  // kPa
    log.values(r, 29) = (r / 2000) % 9;
  }
  return log;
}

/// The generated log on disk, removed when the program ends.
struct BenchFile {
  std::filesystem::path path = std::filesystem::temp_directory_path() /
                               ("tpf_bench_hour_log_" + std::to_string(::getpid()) + ".csv");
  BenchFile() { write_log(path, hour_log()); }
  ~BenchFile() { std::filesystem::remove(path); }
};

const std::filesystem::path& bench_file() {
  static const BenchFile file;
  return file.path;
}

void BM_ReadLogHour(benchmark::State& state) {
  const auto& path = bench_file();
  state.counters["MB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
  for (auto _ : state) {
    Log log = read_log(path);
    benchmark::DoNotOptimize(log.values.data());
  }
}
BENCHMARK(BM_ReadLogHour)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_WriteLogHour(benchmark::State& state) {
  const Log log = hour_log();
  const auto path = std::filesystem::temp_directory_path() / "tpf_bench_hour_log_out.csv";
  for (auto _ : state)
    write_log(path, log);
  std::filesystem::remove(path);
}
BENCHMARK(BM_WriteLogHour)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_LogWriterStreamHour(benchmark::State& state) {
  const Log log = hour_log();
  const auto path = std::filesystem::temp_directory_path() / "tpf_bench_hour_log_stream.csv";
  Eigen::RowVectorXd row(log.values.cols());
  for (auto _ : state) {
    LogWriter writer(path, log.meta, log.columns);
    for (Eigen::Index r = 0; r < log.values.rows(); ++r) {
      row = log.values.row(r);
      writer.write_row({row.data(), static_cast<std::size_t>(row.size())});
    }
    writer.close();
  }
  std::filesystem::remove(path);
}
BENCHMARK(BM_LogWriterStreamHour)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
}  // namespace tpf::offline
