// Per-step latency of the streaming TCN (Release): 16, 32, 64 channels, float and double.
#include <benchmark/benchmark.h>

#include <memory>

#include "offline/compensator_training/tcn_parameters.hpp"
#include "tpf/nn/load_tcn_weights.hpp"
#include "tpf/nn/tcn.hpp"

namespace {

/// One network stepped with the kernel a new Tcn takes (tcn_x86_kernels.hpp), or with `kernel`;
/// its hidden taps in S or bfloat16 (HiddenWeights).
template <typename S, int In, int Hidden, int Out, int Levels = 4, int kernel = -1,
          typename HiddenWeights = S>
void BM_TcnStep(benchmark::State& state) {
  using Engine = tpf::Tcn<S, In, Hidden, Levels, 4, Out, HiddenWeights>;
  auto tcn = std::make_unique<Engine>();
  if (kernel >= 0 && !tcn->use_kernel(tpf::TcnKernel(kernel))) {
    state.SkipWithError("kernel not supported here");
    return;
  }
  tpf::offline::TcnParameters p =
      tpf::offline::init_tcn_parameters({In, Hidden, Levels, 4, Out}, 1);
  for (auto& b : p.blocks)
    b.bias.setConstant(0.05);  // keep most units active
  tpf::TcnWeightFile file = tpf::offline::to_weight_file(p);
  tpf::tcn_weights_from_file(file, *tcn);
  typename Engine::Input x = Engine::Input::LinSpaced(S(-0.5), S(0.5));
  tcn->reset(x);
  S t = 0;
  for (auto _ : state) {
    x(0) = t;
    benchmark::DoNotOptimize(tcn->step(x).data());
    t += S(1e-3);
  }
  state.counters["receptive_field"] = Engine::kReceptiveField;
}

constexpr int kPortable = int(tpf::TcnKernel::Portable), kAvx2 = int(tpf::TcnKernel::Avx2),
              kAvx512 = int(tpf::TcnKernel::Avx512);

// Default shape: kernel 4, 4 levels, R = 46 samples (115 ms at 400 Hz).
BENCHMARK(BM_TcnStep<float, 4, 16, 1>)->Name("TcnStep/per_joint/float/16ch");
BENCHMARK(BM_TcnStep<float, 4, 16, 1, 4, -1, tpf::BFloat16Weights>)
    ->Name("TcnStep/per_joint/bfloat16/16ch");
// The same with each step kernel forced: the portable path (Eigen at the build's flags), AVX2,
// AVX-512.
BENCHMARK(BM_TcnStep<float, 4, 16, 1, 4, kPortable>)->Name("TcnStep/per_joint/float/16ch/portable");
BENCHMARK(BM_TcnStep<float, 4, 16, 1, 4, kAvx2>)->Name("TcnStep/per_joint/float/16ch/avx2");
BENCHMARK(BM_TcnStep<float, 4, 16, 1, 4, kAvx512>)->Name("TcnStep/per_joint/float/16ch/avx512");
BENCHMARK(BM_TcnStep<double, 4, 32, 1, 4, kPortable>)
    ->Name("TcnStep/per_joint/double/32ch/portable");
BENCHMARK(BM_TcnStep<double, 4, 32, 1, 4, kAvx2>)->Name("TcnStep/per_joint/double/32ch/avx2");
BENCHMARK(BM_TcnStep<double, 4, 32, 1, 4, kAvx512>)->Name("TcnStep/per_joint/double/32ch/avx512");
BENCHMARK(BM_TcnStep<float, 4, 32, 1>)->Name("TcnStep/per_joint/float/32ch");
BENCHMARK(BM_TcnStep<float, 4, 64, 1>)->Name("TcnStep/per_joint/float/64ch");
BENCHMARK(BM_TcnStep<double, 4, 16, 1>)->Name("TcnStep/per_joint/double/16ch");
BENCHMARK(BM_TcnStep<double, 4, 32, 1>)->Name("TcnStep/per_joint/double/32ch");
BENCHMARK(BM_TcnStep<double, 4, 64, 1>)->Name("TcnStep/per_joint/double/64ch");
// Five levels: R = 94 samples (235 ms).
BENCHMARK(BM_TcnStep<float, 4, 32, 1, 5>)->Name("TcnStep/per_joint_5_levels/float/32ch");
BENCHMARK(BM_TcnStep<double, 4, 32, 1, 5>)->Name("TcnStep/per_joint_5_levels/double/32ch");
// One network for all four joints: 16 inputs, 4 outputs per head.
BENCHMARK(BM_TcnStep<float, 16, 32, 4>)->Name("TcnStep/all_joints/float/32ch");
BENCHMARK(BM_TcnStep<double, 16, 32, 4>)->Name("TcnStep/all_joints/double/32ch");
BENCHMARK(BM_TcnStep<double, 16, 64, 4>)->Name("TcnStep/all_joints/double/64ch");

}  // namespace
