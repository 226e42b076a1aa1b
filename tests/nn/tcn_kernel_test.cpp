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
TEST(TcnKernel, CompensatorStepsEachNetworkWithItsKernel) {
  constexpr int kJoints = 4;
  using Bank = PerJointTcnCompensator<double, kJoints, 16, 4, float>;
  const offline::TcnArchitecture a{kCompensatorInputsPerJoint, 16, 4, 4, 1};
  for (TcnKernel kernel : {TcnKernel::Portable, TcnKernel::Avx2, TcnKernel::Avx512}) {
    if (!tcn_kernel_supported(kernel)) continue;
    SCOPED_TRACE(name(kernel));
    auto bank = std::make_unique<Bank>();
    auto alone = std::make_unique<std::array<Bank::Network, kJoints>>();
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
      const Bank::Input x = raw.col(t);
      test::AllocationCounter allocations;
      const Bank::Output& y = bank->step(x);
      EXPECT_EQ(allocations.count(), 0u);
      for (int j = 0; j < kJoints; ++j)
        EXPECT_EQ(y[j], double((*alone)[j].step(Bank::joint_input(x, j))[0])) << "t = " << t;
    }
  }
}

}  // namespace
}  // namespace tpf
