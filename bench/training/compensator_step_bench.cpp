// Step cost of the two compensator layouts the trainer can produce, behind the estimator's
// interface: one network for all joints (16 → 32 → 4) against one network per joint (4 × (4 → 32
// → 1)), 4 levels, kernel 4, double. Random weights: the cost does not depend on their values.
#include <benchmark/benchmark.h>

#include <memory>

#include "offline/train/tcn_parameters.hpp"
#include "offline/training/arm_estimator.hpp"
#include "tpf/nn/load_tcn_weights.hpp"

namespace {

using tpf::offline::AllJointsTcn;
using JointTcns = tpf::offline::JointTcns<tpf::offline::kArmHidden>;
using Input = Eigen::Matrix<double, 16, 1>;

tpf::offline::TcnArchitecture architecture(int inputs, int outputs) {
  tpf::offline::TcnArchitecture a;
  a.inputs = inputs;
  a.outputs = outputs;
  return a;
}

template <typename Compensator>
void run(benchmark::State& state, Compensator& c) {
  Input x = Input::Random();
  c.reset(x);
  double sink = 0;
  for (auto _ : state) {
    x[0] += 1e-6;
    sink += c.step(x)[0];
    benchmark::DoNotOptimize(sink);
  }
}

void AllJointsStep(benchmark::State& state) {
  auto c = std::make_unique<AllJointsTcn>();
  tpf::tcn_weights_from_file(
      tpf::offline::to_weight_file(tpf::offline::init_tcn_parameters(architecture(16, 4), 1)),
      c->weights());
  run(state, *c);
}
BENCHMARK(AllJointsStep);

void PerJointStep(benchmark::State& state) {
  auto c = std::make_unique<JointTcns>();
  for (int j = 0; j < 4; ++j)
    tpf::tcn_weights_from_file(
        tpf::offline::to_weight_file(tpf::offline::init_tcn_parameters(architecture(4, 1), j + 1)),
        c->network(j).weights());
  run(state, *c);
}
BENCHMARK(PerJointStep);

}  // namespace
