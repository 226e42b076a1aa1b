// The full estimator step for the 4-joint arm with its 11 pads: kinematics, nominal dynamics and
// friction, skin, state machine, the shipped compensator (one 16-channel TCN per joint, the
// default weights in data/weights) and the contact wrench, on a simulated teaching
// log (motion and contact). Reports the mean per step (Google Benchmark) and, from per-step
// steady_clock timings, the median and p99.9 as counters.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/sim/simulate.hpp"
#include "tpf/estimation/estimator.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/model/effort_unit.hpp"
#include "tpf/model/load_robot.hpp"
#include "tpf/nn/load_tcn_weights.hpp"
#include "tpf/nn/per_joint_tcn_compensator.hpp"
#include "tpf/nn/tcn.hpp"

namespace {

constexpr int N = 4, P = 11;
using Tcn32 = tpf::Tcn<double, tpf::kCompensatorInputsPerJoint * N, 32, 4, 4, N>;
using BenchEstimator = tpf::Estimator<double, N, P, Tcn32>;
/// The layout the tools ship (docs/tcn.md): one 16-channel, 4-level network per joint, evaluated
/// in float; and the same networks in double, for the ratio.
template <typename NetScalar>
using JointNetworks = tpf::PerJointTcnCompensator<double, N, 16, 4, NetScalar>;
template <typename NetScalar>
using ShippedEstimator = tpf::Estimator<double, N, P, JointNetworks<NetScalar>>;
using PlainEstimator = tpf::Estimator<double, N, P>;  // ZeroCompensator: everything but the TCN
using Sample = tpf::EstimatorSample<double, N, P>;

std::string data(const std::string& name) {
  return std::string(TPF_BENCH_DATA_DIR) + "/" + name;
}

/// 20 s of the teaching scenario (seed 1), as estimator samples.
const std::vector<Sample>& samples() {
  static const std::vector<Sample> rows = [] {
    const auto log = tpf::offline::simulate_to_log(
        tpf::offline::load_scenario(data("scenarios/teaching.json")), 1, 20.0);
    const auto model = tpf::load_robot<double, N>(data("arm4.robot.json"));
    std::vector<Sample> out(static_cast<std::size_t>(log.rows()));
    for (Eigen::Index r = 0; r < log.rows(); ++r) {
      Sample& s = out[static_cast<std::size_t>(r)];
      s.t = log.col("t")[r];
      for (int j = 0; j < N; ++j) {
        s.q[j] = log.col(tpf::offline::indexed_name("q", j + 1))[r];
        s.dq[j] = log.col(tpf::offline::indexed_name("dq", j + 1))[r];
        s.effort[j] = log.col(tpf::offline::indexed_name("i", j + 1))[r];
      }
      s.effort = tpf::torque_from_current(model, s.effort);  // mA → N·m
      for (int k = 0; k < P; ++k)
        s.pressure[k] = log.col(tpf::offline::indexed_name("p", k + 1))[r];
    }
    return out;
  }();
  return rows;
}

tpf::NominalModel<double, N> twin_nominal() {
  const auto model = tpf::load_robot<double, N>(data("arm4.robot.json"));
  return tpf::nominal_from_model<N>(
      model, tpf::load_stribeck_parameters<double, N>(data("arm4.friction.json")));
}

tpf::EstimatorParameters<double, N> parameters() {
  tpf::EstimatorParameters<double, N> p;
  p.skin.force_gain = 1.0 / (1.5 * 1000.0 * 0.0025);
  p.nominal_sigma = p.fused_sigma = tpf::JointVector<double, N>::Constant(0.5);  // N·m
  p.static_dead_band = tpf::JointVector<double, N>::Constant(0.1);
  return p;
}

/// The estimator with a seeded random TCN (weights ~ U(−0.05, 0.05)): the arithmetic of a trained
/// one, without a weight file.
std::unique_ptr<BenchEstimator> make_estimator() {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  auto fill = [&](auto& m) {
    for (Eigen::Index i = 0; i < m.size(); ++i)
      m.data()[i] = u(rng);
  };
  auto weights = std::make_unique<Tcn32::Weights>();
  for (auto& w : weights->input_taps)
    fill(w);
  fill(weights->input_projection);
  for (auto& block : weights->taps)
    for (auto& w : block)
      fill(w);
  fill(weights->low_weight);
  fill(weights->high_weight);
  Tcn32 tcn(*weights);
  const auto nominal = twin_nominal();
  return std::make_unique<BenchEstimator>(
      nominal, tpf::load_pads(data("arm4.pads.json"), nominal.model), parameters(), tcn);
}

/// The estimator with the default per-joint weights data/weights/arm4.tcn.joint<j>.json.
template <typename NetScalar>
std::unique_ptr<ShippedEstimator<NetScalar>> make_shipped_estimator() {
  JointNetworks<NetScalar> tcns;
  for (int j = 0; j < N; ++j)
    tpf::load_tcn_weights(data("weights/arm4.tcn.joint" + std::to_string(j + 1) + ".json"),
                          tcns.network(j));
  const auto nominal = twin_nominal();
  return std::make_unique<ShippedEstimator<NetScalar>>(
      nominal, tpf::load_pads(data("arm4.pads.json"), nominal.model), parameters(), tcns);
}

std::unique_ptr<PlainEstimator> make_plain_estimator() {
  const auto nominal = twin_nominal();
  return std::make_unique<PlainEstimator>(
      nominal, tpf::load_pads(data("arm4.pads.json"), nominal.model), parameters());
}

/// The median of `ns` (sorted in place).
double median(std::vector<double>& ns) {
  std::sort(ns.begin(), ns.end());
  return ns[ns.size() / 2];
}

/// The median of an empty interval between two steady_clock reads [ns], what each step's time
/// below includes besides the step (≈ 20 ns here; the clock advances in steps of ≈ 10 ns).
double clock_read_ns() {
  std::vector<double> ns(100000);
  for (double& d : ns) {
    const auto start = std::chrono::steady_clock::now();
    const auto stop = std::chrono::steady_clock::now();
    d = std::chrono::duration<double, std::nano>(stop - start).count();
  }
  return median(ns);
}

/// Replays the teaching log through `est` (time keeps advancing), one timed update per iteration;
/// median, p99, p99.9 and max of the per-step wall time as counters, and the median and share of
/// the steps by where the wrench was estimated (`median_ns_no_wrench`, `median_ns_link<k>`: a pad
/// of link k, whose Jacobian has k columns that can be nonzero); `clock_ns`, what the clock
/// reads add to each step's time.
template <typename Est, typename Row = Sample>
void time_steps(benchmark::State& state, Est& est, const std::vector<Row>& rows = samples()) {
  std::vector<double> ns;
  ns.reserve(1 << 22);
  state.counters["clock_ns"] = clock_read_ns();
  std::vector<int> wrench_link;  // per timed step: the wrench pad's link, 0 without a wrench
  wrench_link.reserve(ns.capacity());
  std::size_t r = 0;
  double t_offset = 0;
  int wrenches = 0;
  for (auto _ : state) {
    Row s = rows[r];
    s.t += t_offset;
    const auto start = std::chrono::steady_clock::now();
    const auto& out = est.update(s);
    const auto stop = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(out.wrench.force_world);
    wrenches += out.wrench.pad >= 0;
    if (ns.size() < ns.capacity()) {
      ns.push_back(std::chrono::duration<double, std::nano>(stop - start).count());
      wrench_link.push_back(out.wrench.pad >= 0 ? est.skin().geometry(out.wrench.pad).link : 0);
    }
    if (++r == rows.size()) {
      r = 0;
      t_offset += rows.back().t - rows.front().t + 0.0025;
    }
  }
  std::map<int, std::vector<double>> by_link;
  for (std::size_t k = 0; k < ns.size(); ++k)
    by_link[wrench_link[k]].push_back(ns[k]);
  for (auto& [link, times] : by_link) {
    const std::string name = link == 0 ? "no_wrench" : "link" + std::to_string(link);
    state.counters["share_" + name] =
        static_cast<double>(times.size()) / static_cast<double>(ns.size());
    state.counters["median_ns_" + name] = median(times);
  }
  std::sort(ns.begin(), ns.end());
  auto quantile = [&](double q) { return ns[static_cast<std::size_t>(q * (ns.size() - 1))]; };
  state.counters["median_ns"] = quantile(0.5);
  state.counters["p99_ns"] = quantile(0.99);
  state.counters["p99.9_ns"] = quantile(0.999);
  state.counters["max_ns"] = ns.back();
  state.counters["contact_share"] = static_cast<double>(wrenches) / static_cast<double>(ns.size());
}

void BM_EstimatorStep(benchmark::State& state) {
  auto est = make_estimator();
  time_steps(state, *est);
}
BENCHMARK(BM_EstimatorStep)->Iterations(400000)->Unit(benchmark::kNanosecond);

/// The shipped compensator (float networks whose hidden taps are bfloat16, the tools' and
/// examples' PerJointTcn<BFloat16Weights, 16>), the same networks with float taps and in double;
/// each network steps with the kernel a new Tcn takes (tcn_x86_kernels.hpp), or with `kernel`.
template <typename NetScalar, int kernel = -1>
void BM_EstimatorStepShippedCompensator(benchmark::State& state) {
  auto est = make_shipped_estimator<NetScalar>();
  for (int j = 0; j < N; ++j)
    if (kernel >= 0 && !est->compensator().network(j).use_kernel(tpf::TcnKernel(kernel))) {
      state.SkipWithError("kernel not supported here");
      return;
    }
  time_steps(state, *est);
}
BENCHMARK(BM_EstimatorStepShippedCompensator<tpf::BFloat16Weights>)
    ->Name("BM_EstimatorStepShippedCompensator<bfloat16>")
    ->Iterations(400000)
    ->Unit(benchmark::kNanosecond);
BENCHMARK(BM_EstimatorStepShippedCompensator<float>)
    ->Iterations(400000)
    ->Unit(benchmark::kNanosecond);
BENCHMARK(BM_EstimatorStepShippedCompensator<double>)
    ->Iterations(400000)
    ->Unit(benchmark::kNanosecond);
BENCHMARK(BM_EstimatorStepShippedCompensator<float, int(tpf::TcnKernel::Portable)>)
    ->Name("BM_EstimatorStepShippedCompensator<float>/portable")
    ->Iterations(400000)
    ->Unit(benchmark::kNanosecond);

void BM_EstimatorStepWithoutCompensator(benchmark::State& state) {
  auto est = make_plain_estimator();
  time_steps(state, *est);
}
BENCHMARK(BM_EstimatorStepWithoutCompensator)->Iterations(400000)->Unit(benchmark::kNanosecond);

/// The shipped compensator's estimator at a run-time joint and pad count (Eigen::Dynamic, what
/// the offline tools run for any arm) on the same log: the cost of sizes chosen at start-up.
void BM_EstimatorStepRunTimeSize(benchmark::State& state) {
  constexpr int X = Eigen::Dynamic;
  using Networks = tpf::PerJointTcnCompensator<double, X, 16, 4, tpf::BFloat16Weights>;
  const auto nominal = tpf::joint_count_cast<X>(twin_nominal());
  auto est = std::make_unique<tpf::Estimator<double, X, X, Networks>>(
      nominal, tpf::load_pads(data("arm4.pads.json"), nominal.model),
      tpf::joint_count_cast<X>(parameters()));
  for (int j = 0; j < N; ++j)
    tpf::load_tcn_weights(data("weights/arm4.tcn.joint" + std::to_string(j + 1) + ".json"),
                          est->compensator().network(j));
  std::vector<tpf::EstimatorSample<double, X, X>> rows(samples().size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const Sample& f = samples()[r];
    rows[r].resize(N, P);
    rows[r].t = f.t;
    rows[r].q = f.q;
    rows[r].dq = f.dq;
    rows[r].effort = f.effort;
    rows[r].pressure = f.pressure;
  }
  time_steps(state, *est, rows);
}
BENCHMARK(BM_EstimatorStepRunTimeSize)->Iterations(400000)->Unit(benchmark::kNanosecond);

/// The 7-joint Kinova Gen3 without skin (P = 0, no compensator): its robot and friction files,
/// 20 s of a multi-sine motion (400 Hz, every joint moving) with the nominal model's own effort
/// plus a slow push on joint 2 (an external torque half of the time).
void BM_EstimatorStepKinova7NoPads(benchmark::State& state) {
  constexpr int J = 7;
  using Kinova = tpf::Estimator<double, J, 0>;
  using KinovaSample = tpf::EstimatorSample<double, J, 0>;
  const auto model = tpf::load_robot<double, J>(data("real/kinova-gen3/gen3.robot.json"));
  const auto nominal = tpf::nominal_from_model<J>(
      model, tpf::load_stribeck_parameters<double, J>(data("real/kinova-gen3/gen3.friction.json")));
  const auto links = tpf::nominal_links(nominal);
  tpf::Data<double, J> d(nominal.model);
  std::vector<KinovaSample> rows(8000);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    KinovaSample& s = rows[k];
    s.t = 0.0025 * static_cast<double>(k);
    tpf::JointVector<double, J> ddq;
    for (int j = 0; j < J; ++j) {
      const double w = 2.0 * 3.141592653589793 * (0.1 + 0.03 * j), a = 0.4 + 0.05 * j;
      s.q[j] = a * std::sin(w * s.t + j);
      s.dq[j] = a * w * std::cos(w * s.t + j);
      ddq[j] = -a * w * w * std::sin(w * s.t + j);
    }
    tpf::JointVector<double, J> rigid, friction;
    tpf::predict_effort(nominal, links, d, s.q, s.dq, ddq, rigid, friction);
    s.effort = rigid + friction;
    s.effort[1] += 5.0 * std::max(0.0, std::sin(0.7 * s.t));  // a push on joint 2 [N·m]
  }
  auto est = std::make_unique<Kinova>(nominal, std::vector<tpf::Pad>{},
                                      tpf::EstimatorParameters<double, J>{});
  time_steps(state, *est, rows);
}
BENCHMARK(BM_EstimatorStepKinova7NoPads)->Iterations(400000)->Unit(benchmark::kNanosecond);

/// The nominal model alone on the log's states: the link form (per cycle) against the regressor
/// form it replaced.
template <bool kLinkForm>
void BM_PredictEffort(benchmark::State& state) {
  const auto& rows = samples();
  const auto nominal = twin_nominal();
  const auto links = tpf::nominal_links(nominal);
  tpf::Data<double, N> d(nominal.model);
  tpf::JointVector<double, N> rigid, friction, ddq = tpf::JointVector<double, N>::Constant(0.3);
  std::size_t r = 0;
  for (auto _ : state) {
    const Sample& s = rows[r];
    if constexpr (kLinkForm)
      tpf::predict_effort(nominal, links, d, s.q, s.dq, ddq, rigid, friction);
    else
      tpf::predict_effort_by_regressor(nominal, d, s.q, s.dq, ddq, rigid, friction);
    benchmark::DoNotOptimize(rigid);
    benchmark::DoNotOptimize(friction);
    if (++r == rows.size()) r = 0;
  }
}
BENCHMARK(BM_PredictEffort<true>)->Name("BM_PredictEffort/link_form");
BENCHMARK(BM_PredictEffort<false>)->Name("BM_PredictEffort/regressor_form");

}  // namespace
