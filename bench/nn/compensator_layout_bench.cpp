// Step cost of the whole friction compensator of the 4-joint arm, per layout, behind the
// estimator's interface (FrictionCompensator, 20 inputs → 4 outputs): one network for all joints
// (20 → 32 → 4) against one network per joint (4 × (5 → H → 1), H = 16 or 32), float and double,
// 4 levels, kernel 4. Random weights: the cost does not depend on their values.
#include <benchmark/benchmark.h>

#include <memory>

#include "offline/compensator_training/tcn_parameters.hpp"
#include "tpf/nn/load_tcn_weights.hpp"
#include "tpf/nn/per_joint_tcn_compensator.hpp"
#include "tpf/nn/tcn.hpp"

namespace {

constexpr int kJoints = 4;
constexpr int kInputs = tpf::kCompensatorInputsPerJoint;

tpf::TcnWeightFile random_file(int inputs, int hidden, int outputs, std::uint64_t seed) {
  tpf::offline::TcnParameters p =
      tpf::offline::init_tcn_parameters({inputs, hidden, 4, 4, outputs}, seed);
  for (auto& b : p.blocks)
    b.bias.setConstant(0.05);  // keep most units active
  return tpf::offline::to_weight_file(p);
}

template <typename S, int Joints = kJoints, typename Compensator>
void run(benchmark::State& state, Compensator& c) {
  tpf::CompensatorInput<S, Joints> x = tpf::CompensatorInput<S, Joints>::LinSpaced(-0.5, 0.5);
  c.reset(x);
  S t = 0;
  for (auto _ : state) {
    x(0) = t;
    benchmark::DoNotOptimize(c.step(x).data());
    t += S(1e-3);
  }
}

template <typename S>
void AllJoints(benchmark::State& state) {
  auto c = std::make_unique<tpf::Tcn<S, kInputs * kJoints, 32, 4, 4, kJoints>>();
  tpf::tcn_weights_from_file(random_file(kInputs * kJoints, 32, kJoints, 1), *c);
  run<S>(state, *c);
}

/// One network per joint, each stepping with the kernel a new Tcn takes, or with `kernel`; the
/// networks in S or (NetScalar = BFloat16Weights) float with bfloat16 hidden taps.
template <typename S, int Hidden, int kernel = -1, typename NetScalar = S>
void PerJoint(benchmark::State& state) {
  auto c = std::make_unique<tpf::PerJointTcnCompensator<S, kJoints, Hidden, 4, NetScalar>>();
  for (int j = 0; j < kJoints; ++j) {
    tpf::tcn_weights_from_file(random_file(kInputs, Hidden, 1, j + 1), c->network(j));
    if (kernel >= 0 && !c->network(j).use_kernel(tpf::TcnKernel(kernel))) {
      state.SkipWithError("kernel not supported here");
      return;
    }
  }
  run<S>(state, *c);
}

/// The shipped shape (float, 16 channels, ≈ 14 kB of weights each) with 1–4 networks: the step
/// grows by one network's time while their weights fit the L1 cache, by more once they do not.
template <int Networks>
void PerJointNetworks(benchmark::State& state) {
  auto c = std::make_unique<tpf::PerJointTcnCompensator<float, Networks, 16, 4>>();
  for (int j = 0; j < Networks; ++j)
    tpf::tcn_weights_from_file(random_file(kInputs, 16, 1, j + 1), c->network(j));
  run<float, Networks>(state, *c);
}

/// The same per-joint networks stepped one after another (what PerJointTcnCompensator::step did
/// before it interleaved them, Tcn::step_together): the same results, bit for bit.
template <typename S, int Hidden>
void PerJointOneAfterAnother(benchmark::State& state) {
  using Bank = tpf::PerJointTcnCompensator<S, kJoints, Hidden, 4>;
  auto c = std::make_unique<Bank>();
  for (int j = 0; j < kJoints; ++j)
    tpf::tcn_weights_from_file(random_file(kInputs, Hidden, 1, j + 1), c->network(j));
  tpf::CompensatorInput<S, kJoints> x = tpf::CompensatorInput<S, kJoints>::LinSpaced(-0.5, 0.5);
  c->reset(x);
  S t = 0;
  for (auto _ : state) {
    x(0) = t;
    for (int j = 0; j < kJoints; ++j)
      benchmark::DoNotOptimize(c->network(j).step(Bank::joint_input(x, j)).data());
    t += S(1e-3);
  }
}

BENCHMARK(AllJoints<float>)->Name("Compensator/all_joints_32ch/float");
BENCHMARK(AllJoints<double>)->Name("Compensator/all_joints_32ch/double");
BENCHMARK(PerJoint<float, 16>)->Name("Compensator/per_joint_16ch/float");
BENCHMARK(PerJoint<float, 16, -1, tpf::BFloat16Weights>)
    ->Name("Compensator/per_joint_16ch/bfloat16");
BENCHMARK(PerJoint<float, 16, int(tpf::TcnKernel::Portable)>)
    ->Name("Compensator/per_joint_16ch/float/portable");
BENCHMARK(PerJoint<double, 16>)->Name("Compensator/per_joint_16ch/double");
BENCHMARK(PerJoint<float, 32>)->Name("Compensator/per_joint_32ch/float");
BENCHMARK(PerJoint<double, 32>)->Name("Compensator/per_joint_32ch/double");
BENCHMARK(PerJointNetworks<1>)->Name("Compensator/per_joint_16ch/float/networks:1");
BENCHMARK(PerJointNetworks<2>)->Name("Compensator/per_joint_16ch/float/networks:2");
BENCHMARK(PerJointNetworks<3>)->Name("Compensator/per_joint_16ch/float/networks:3");
BENCHMARK(PerJointOneAfterAnother<float, 16>)
    ->Name("Compensator/per_joint_16ch/float/one_after_another");
BENCHMARK(PerJointOneAfterAnother<double, 32>)
    ->Name("Compensator/per_joint_32ch/double/one_after_another");

}  // namespace
