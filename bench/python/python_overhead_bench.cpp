// The C++ side of the Python module's overhead (bench/python/python_overhead.py runs this program
// and the same calls from Python in one run, and reports the difference and the ratio):
// - RNEA of the 7-DoF Kinova Gen3 at the run-time joint count (Model<double, Eigen::Dynamic>, as
//   tpf.Robot holds it), q = 0, q̇ = q̈ = 1;
// - the replay estimator (arm4: nominal model, estimator file, the shipped per-joint TCN, no skin)
//   over a synthetic log of TPF_BENCH_REPLAY_SECONDS seconds (default 3600) at 400 Hz: samples
//   built from the arrays, the estimator run and its trace recorded, as tpf.estimate does.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "offline/replay/replay_estimator.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/estimation/load_estimator.hpp"
#include "tpf/model/load_robot.hpp"

namespace {

const std::string kData = TPF_BENCH_DATA_DIR;

void BM_RneaGen3Dynamic(benchmark::State& state) {
  const auto model =
      tpf::load_robot<double, Eigen::Dynamic>(kData + "/real/kinova-gen3/gen3.robot.json");
  tpf::Data<double, Eigen::Dynamic> data(model);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(7), dq = Eigen::VectorXd::Ones(7),
                        ddq = Eigen::VectorXd::Ones(7);
  Eigen::VectorXd tau(7);
  for (auto _ : state) {
    tau = tpf::rnea(model, data, q, dq, ddq);
    benchmark::DoNotOptimize(tau.data());
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_RneaGen3Dynamic);

/// The synthetic log python_overhead.py builds too: t_k = k/400 s; joint j (0-based) at
/// ω_j = 2π(0.2 + 0.1j): q = 0.5 sin ω t, q̇ = 0.5 ω cos ω t, τ = 2 sin(ω t + 0.3) [N·m].
struct Motion {
  Eigen::VectorXd t;
  Eigen::MatrixXd q, dq, tau;  // rows × joints
};

Motion synthetic_motion(double seconds, int joints) {
  const auto rows = static_cast<Eigen::Index>(std::lround(seconds * 400.0));
  Motion m{Eigen::VectorXd(rows), Eigen::MatrixXd(rows, joints), Eigen::MatrixXd(rows, joints),
           Eigen::MatrixXd(rows, joints)};
  for (Eigen::Index k = 0; k < rows; ++k) {
    m.t[k] = static_cast<double>(k) / 400.0;
    for (int j = 0; j < joints; ++j) {
      const double w = 2 * std::numbers::pi * (0.2 + 0.1 * j);
      m.q(k, j) = 0.5 * std::sin(w * m.t[k]);
      m.dq(k, j) = 0.5 * w * std::cos(w * m.t[k]);
      m.tau(k, j) = 2 * std::sin(w * m.t[k] + 0.3);
    }
  }
  return m;
}

double replay_seconds() {
  const char* s = std::getenv("TPF_BENCH_REPLAY_SECONDS");
  return s ? std::atof(s) : 3600.0;
}

void BM_ReplayEstimatorOverLog(benchmark::State& state) {
  const tpf::EstimatorFiles files{kData + "/arm4.params.json", kData + "/arm4.robot.json", "",
                                  kData + "/arm4.estimator.json", kData + "/weights/arm4.tcn.json"};
  const Motion m = synthetic_motion(replay_seconds(), 4);
  for (auto _ : state) {
    const tpf::offline::ReplaySetup setup = tpf::load_estimator_setup(files);
    std::vector<tpf::offline::ReplaySample> samples(static_cast<std::size_t>(m.t.size()));
    for (Eigen::Index k = 0; k < m.t.size(); ++k) {
      auto& s = samples[static_cast<std::size_t>(k)];
      s.resize(4, 0);
      s.t = m.t[k];
      s.q = m.q.row(k).transpose();
      s.dq = m.dq.row(k).transpose();
      s.effort = m.tau.row(k).transpose();
    }
    const tpf::offline::EstimatorTrace trace = tpf::offline::replay_estimator(setup, samples);
    benchmark::DoNotOptimize(trace.residual.data());
  }
  state.counters["rows"] = static_cast<double>(m.t.size());
}
BENCHMARK(BM_ReplayEstimatorOverLog)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
