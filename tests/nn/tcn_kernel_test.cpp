// The TCN step in AVX2 / AVX-512 registers (tcn_x86_kernels.hpp) against the portable step and
// the double network, for every kernel this CPU runs (each forced through Tcn::use_kernel).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <tuple>

#include "support/allocation_counter.hpp"
#include "tcn_test_support.hpp"
#include "tpf/nn/per_joint_tcn_compensator.hpp"
#include "tpf/nn/tcn.hpp"

namespace tpf {
namespace {

constexpr TcnKernel kWide[] = {TcnKernel::Avx2, TcnKernel::Avx512};

const char* name(TcnKernel k) {
  return k == TcnKernel::Avx2 ? "AVX2" : k == TcnKernel::Avx512 ? "AVX-512" : "portable";
}

/// Largest |a − b| over the low and high heads of every step.
struct Deviation {
  double vs_portable = 0, vs_double = 0, largest = 0;
};

/// Streams `steps` random inputs (one of them non-finite) through the network `p` three ways: in
/// S with `kernel`, in S on the portable path, in double on the portable path.
template <typename S, int In, int Hidden, int Levels, int Out>
Deviation deviation(const offline::TcnParameters& p, TcnKernel kernel, std::uint64_t seed,
                    Eigen::Index steps = 200) {
  using Engine = Tcn<S, In, Hidden, Levels, 4, Out>;
  using Exact = Tcn<double, In, Hidden, Levels, 4, Out>;
  auto wide = std::make_unique<Engine>(), portable = std::make_unique<Engine>();
  auto exact = std::make_unique<Exact>();
  test::load_parameters(p, *wide);
  test::load_parameters(p, *portable);
  test::load_parameters(p, *exact);
  EXPECT_TRUE(wide->use_kernel(kernel));
  EXPECT_EQ(wide->kernel(), kernel);
  EXPECT_TRUE(portable->use_kernel(TcnKernel::Portable));
  EXPECT_TRUE(exact->use_kernel(TcnKernel::Portable));

  Eigen::MatrixXd raw = test::random_inputs(In, steps, seed);
  raw(In - 1, steps / 2) = std::numeric_limits<double>::quiet_NaN();
  wide->reset(raw.col(0).cast<S>());
  portable->reset(raw.col(0).cast<S>());
  exact->reset(raw.col(0));
  Deviation d;
  for (Eigen::Index t = 1; t < steps; ++t) {
    const typename Engine::Input x = raw.col(t).cast<S>();
    test::AllocationCounter allocations;
    wide->step(x);
    EXPECT_EQ(allocations.count(), 0u);
    portable->step(x);
    exact->step(raw.col(t));
    for (const auto& [w, q, e] : {std::tuple{wide->low(), portable->low(), exact->low()},
                                  std::tuple{wide->high(), portable->high(), exact->high()}}) {
      const Eigen::VectorXd a = w.template cast<double>(), b = q.template cast<double>();
      d.vs_portable = std::max(d.vs_portable, (a - b).cwiseAbs().maxCoeff());
      d.vs_double = std::max(d.vs_double, (a - e).cwiseAbs().maxCoeff());
      d.largest = std::max(d.largest, e.cwiseAbs().maxCoeff());
    }
    EXPECT_EQ(wide->output(), (wide->low() + wide->high()).eval());
  }
  EXPECT_EQ(wide->skipped_inputs(), 1);
  return d;
}

/// For every kernel this CPU runs that fits the shape: the kernel's heads equal the portable
/// step's and the double network's to `relative`·(largest output), on three random networks;
/// and a network with one tap of its last block zeroed (what a missing tap, a wrong dilation or
/// a wrong column amounts to) is off by far more than that bound.
template <typename S, int In, int Hidden, int Levels, int Out>
void expect_kernels_match(double relative) {
  const offline::TcnArchitecture a{In, Hidden, Levels, 4, Out};
  int ran = 0;
  for (TcnKernel kernel : kWide) {
    const bool fits = tcn_kernel_fits<S, Hidden>(kernel);
    if (!fits || !tcn_kernel_supported(kernel)) {
      EXPECT_FALSE((Tcn<S, In, Hidden, Levels, 4, Out>().use_kernel(kernel)));
      continue;
    }
    ++ran;
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      const offline::TcnParameters p = test::random_tcn_parameters(a, 100 * seed);
      const Deviation d = deviation<S, In, Hidden, Levels, Out>(p, kernel, seed);
      SCOPED_TRACE(testing::Message() << name(kernel) << ", seed " << seed);
      EXPECT_GT(d.largest, 0.5);  // live networks
      EXPECT_LE(d.vs_portable, relative * d.largest);
      EXPECT_LE(d.vs_double, relative * d.largest);
      EXPECT_GT(d.vs_portable + d.vs_double, 0.0);  // not the portable path in disguise

      offline::TcnParameters wrong = p;
      wrong.blocks[Levels - 1].taps[3].setZero();  // the longest lag of the last block
      const offline::TcnParameters& right = p;
      auto good = std::make_unique<Tcn<double, In, Hidden, Levels, 4, Out>>();
      auto bad = std::make_unique<Tcn<double, In, Hidden, Levels, 4, Out>>();
      test::load_parameters(right, *good);
      test::load_parameters(wrong, *bad);
      const Eigen::MatrixXd raw = test::random_inputs(In, 100, seed + 50);
      good->reset(raw.col(0));
      bad->reset(raw.col(0));
      double off = 0;
      for (Eigen::Index t = 1; t < raw.cols(); ++t)
        off = std::max(off, (good->step(raw.col(t)) - bad->step(raw.col(t))).cwiseAbs().maxCoeff());
      EXPECT_GT(off, 1000 * relative * d.largest);
    }
  }
  if (ran == 0) GTEST_SKIP() << "no wide kernel for this shape on this CPU or build";
}

// The shipped compensator's network: 5 inputs, 16 float channels, 4 levels (AVX2: 2 registers per
// hidden vector, AVX-512: 1).
TEST(TcnKernel, Float16ChannelsMatchesPortableAndDouble) {
  expect_kernels_match<float, kCompensatorInputsPerJoint, 16, 4, 1>(1e-5);
}
// 8 float channels fill one AVX2 register and no AVX-512 one (that kernel refuses the shape).
TEST(TcnKernel, Float8ChannelsMatchesPortableAndDouble) {
  expect_kernels_match<float, 4, 8, 3, 1>(1e-5);
}
// 32 double channels: 8 AVX2 / 4 AVX-512 registers per hidden vector.
TEST(TcnKernel, Double32ChannelsMatchesPortable) {
  expect_kernels_match<double, 4, 32, 4, 1>(1e-12);
}
// One network for all joints: 4 outputs per head (the heads on the portable path).
TEST(TcnKernel, FloatAllJointsMatchesPortableAndDouble) {
  expect_kernels_match<float, 20, 32, 4, 4>(1e-5);
}

/// `p` with the hidden blocks' taps as a BFloat16Weights network holds them: columns paired
/// (bfloat16_pair, tests/nn/bfloat16_test.cpp), each within half a bfloat16 step.
offline::TcnParameters hidden_taps_in_bfloat16(offline::TcnParameters p) {
  for (std::size_t l = 1; l < p.blocks.size(); ++l)
    for (auto& tap : p.blocks[l].taps)
      for (Eigen::Index c = 0; c < tap.cols(); c += 2)
        for (Eigen::Index r = 0; r < tap.rows(); ++r) {
          const BFloat16Pair pair = bfloat16_pair(float(tap(r, c)), float(tap(r, c + 1)));
          tap(r, c) = pair_even(pair);
          tap(r, c + 1) = pair_odd(pair);
        }
  return p;
}

// A network with bfloat16 hidden taps is, with every kernel (the paired loads unpacked in
// registers, the portable path on the rounded taps), the float network of the rounded taps bit
// for bit; and it differs from the unrounded network by the rounding's size (≤ 2^-8 of each tap:
// neither nothing nor more than a few per mille of the output). Allocation-free.
TEST(TcnKernel, BFloat16WeightsAreTheFloatNetworkOfRoundedTaps) {
  using Paired = Tcn<float, kCompensatorInputsPerJoint, 16, 4, 4, 1, BFloat16Weights>;
  using Float = Tcn<float, kCompensatorInputsPerJoint, 16, 4, 4, 1>;
  const offline::TcnParameters p =
      test::random_tcn_parameters({kCompensatorInputsPerJoint, 16, 4, 4, 1}, 41);
  for (TcnKernel kernel : {TcnKernel::Portable, TcnKernel::Avx2, TcnKernel::Avx512}) {
    if (!tcn_kernel_supported(kernel)) continue;
    SCOPED_TRACE(name(kernel));
    auto paired = std::make_unique<Paired>();
    auto rounded = std::make_unique<Float>(), exact = std::make_unique<Float>();
    test::load_parameters(p, *paired);
    test::load_parameters(hidden_taps_in_bfloat16(p), *rounded);
    test::load_parameters(p, *exact);
    for (std::size_t l = 0; l < paired->weights().taps.size(); ++l)
      for (std::size_t j = 0; j < 4; ++j)
        ASSERT_EQ(paired->weights().taps[l][j], rounded->weights().taps[l][j]);
    ASSERT_TRUE(paired->use_kernel(kernel) && rounded->use_kernel(kernel) &&
                exact->use_kernel(kernel));
    const Eigen::MatrixXd raw = test::random_inputs(kCompensatorInputsPerJoint, 200, 42);
    paired->reset(raw.col(0).cast<float>());
    rounded->reset(raw.col(0).cast<float>());
    exact->reset(raw.col(0).cast<float>());
    double off = 0, largest = 0;
    for (Eigen::Index t = 1; t < raw.cols(); ++t) {
      const Float::Input x = raw.col(t).cast<float>();
      test::AllocationCounter allocations;
      paired->step(x);
      EXPECT_EQ(allocations.count(), 0u);
      rounded->step(x);
      exact->step(x);
      EXPECT_EQ(paired->low(), rounded->low()) << "t = " << t;
      EXPECT_EQ(paired->high(), rounded->high()) << "t = " << t;
      off = std::max(off, double(std::abs(paired->output()[0] - exact->output()[0])));
      largest = std::max(largest, double(std::abs(exact->output()[0])));
    }
    EXPECT_GT(largest, 0.5);
    EXPECT_GT(off, 1e-5 * largest);
    EXPECT_LT(off, 1e-2 * largest);
  }
}

// A new network takes the widest kernel that fits and this CPU runs.
TEST(TcnKernel, NewNetworkUsesTheWidestSupportedKernel) {
  const TcnKernel k = Tcn<float, 5, 16, 4>().kernel();
  EXPECT_TRUE(tcn_kernel_supported(k));
#ifdef TPF_TCN_DISPATCH
  const TcnKernel widest = tcn_kernel_supported(TcnKernel::Avx512) ? TcnKernel::Avx512
                           : tcn_kernel_supported(TcnKernel::Avx2) ? TcnKernel::Avx2
                                                                   : TcnKernel::Portable;
  EXPECT_EQ(k, widest);
#else
  EXPECT_EQ(k, TcnKernel::Portable);  // not x86-64 (GCC, clang): the compile-time path
#endif
  EXPECT_EQ((Tcn<float, 5, 12, 4>().kernel()), TcnKernel::Portable);  // 48 bytes: no kernel fits
}

// The per-joint compensator with each kernel forced: each network steps with its kernel, equal
// bit for bit to the same network stepped alone with that kernel, allocation-free.
template <typename NetScalar>
void expect_each_network_steps_with_its_kernel() {
  constexpr int kJoints = 4;
  using Bank = PerJointTcnCompensator<double, kJoints, 16, 4, NetScalar>;
  const offline::TcnArchitecture a{kCompensatorInputsPerJoint, 16, 4, 4, 1};
  for (TcnKernel kernel : {TcnKernel::Portable, TcnKernel::Avx2, TcnKernel::Avx512}) {
    if (!tcn_kernel_supported(kernel)) continue;
    SCOPED_TRACE(name(kernel));
    auto bank = std::make_unique<Bank>();
    auto alone = std::make_unique<std::array<typename Bank::Network, kJoints>>();
    for (int j = 0; j < kJoints; ++j) {
      const offline::TcnParameters p = test::random_tcn_parameters(a, 300 + j);
      test::load_parameters(p, bank->network(j));
      test::load_parameters(p, (*alone)[j]);
      ASSERT_TRUE(bank->network(j).use_kernel(kernel));
      ASSERT_TRUE((*alone)[j].use_kernel(kernel));
    }
    const Eigen::MatrixXd raw = test::random_inputs(kCompensatorInputsPerJoint * kJoints, 60, 301);
    bank->reset(raw.col(0));
    for (int j = 0; j < kJoints; ++j)
      (*alone)[j].reset(Bank::joint_input(raw.col(0), j));
    for (Eigen::Index t = 1; t < raw.cols(); ++t) {
      const typename Bank::Input x = raw.col(t);
      test::AllocationCounter allocations;
      const typename Bank::Output& y = bank->step(x);
      EXPECT_EQ(allocations.count(), 0u);
      for (int j = 0; j < kJoints; ++j)
        EXPECT_EQ(y[j], double((*alone)[j].step(Bank::joint_input(x, j))[0])) << "t = " << t;
    }
  }
}
TEST(TcnKernel, CompensatorStepsEachNetworkWithItsKernel) {
  expect_each_network_steps_with_its_kernel<float>();
}
TEST(TcnKernel, BFloat16CompensatorStepsEachNetworkWithItsKernel) {
  expect_each_network_steps_with_its_kernel<BFloat16Weights>();
}

}  // namespace
}  // namespace tpf
