// Streaming TCN inference against a naive full-window network; causality; prewarm; allocations.
#include <gtest/gtest.h>

#include <limits>
#include <memory>

#include "support/allocation_counter.hpp"
#include "tcn_test_support.hpp"
#include "tpf/nn/tcn.hpp"

namespace tpf {
namespace {

using offline::TcnArchitecture;

template <typename Engine>
Eigen::MatrixXd stream(Engine& tcn, const Eigen::MatrixXd& raw, Eigen::Index from) {
  Eigen::MatrixXd out(2 * Engine::kOutputs, raw.cols() - from);
  for (Eigen::Index t = from; t < raw.cols(); ++t) {
    tcn.step(raw.col(t).cast<typename Engine::Scalar>());
    out.col(t - from) << tcn.low().template cast<double>(), tcn.high().template cast<double>();
    EXPECT_EQ(tcn.output(), (tcn.low() + tcn.high()).eval());
  }
  return out;
}

/// The same random network in the float and the double engine, streamed over `steps` random
/// inputs: the largest |float − double| output and the largest |double| output.
struct FloatDeviation {
  double max_difference;
  double scale;
};
template <int In, int H, int L>
FloatDeviation float_deviation(std::uint64_t parameter_seed, std::uint64_t input_seed,
                               Eigen::Index steps) {
  const TcnArchitecture a{In, H, L, 4, 1};
  const offline::TcnParameters p = test::random_tcn_parameters(a, parameter_seed);
  Tcn<double, In, H, L> d;
  Tcn<float, In, H, L> f;
  test::load_parameters(p, d);
  test::load_parameters(p, f);
  const Eigen::MatrixXd raw = test::random_inputs(In, steps, input_seed);
  d.reset(raw.col(0));
  f.reset(raw.col(0).cast<float>());
  const Eigen::MatrixXd od = stream(d, raw, 0), of = stream(f, raw, 0);
  return {(od - of).cwiseAbs().maxCoeff(), od.cwiseAbs().maxCoeff()};
}

template <typename Engine>
void expect_streaming_equals_naive(const TcnArchitecture& a, std::uint64_t seed,
                                   Eigen::Index steps = 300) {
  const offline::TcnParameters p = test::random_tcn_parameters(a, seed);
  auto tcn = std::make_unique<Engine>();
  test::load_parameters(p, *tcn);
  ASSERT_EQ(Engine::kReceptiveField, a.receptive_field());

  // Steady prefix of R − 1 samples = what reset() assumes, then `steps` random samples.
  const Eigen::Index r = a.receptive_field();
  Eigen::MatrixXd raw(a.inputs, r - 1 + steps);
  const Eigen::VectorXd steady = test::random_inputs(a.inputs, 1, seed + 7);
  raw.leftCols(r - 1).colwise() = steady;
  raw.rightCols(steps) = test::random_inputs(a.inputs, steps, seed + 8);

  const Eigen::MatrixXd naive = test::naive_tcn(p, raw);
  ASSERT_EQ(naive.cols(), steps);
  tcn->reset(steady.cast<typename Engine::Scalar>());
  const Eigen::MatrixXd streamed = stream(*tcn, raw, r - 1);
  const double scale = naive.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.1);  // a dead network would prove nothing
  EXPECT_LT((streamed - naive).cwiseAbs().maxCoeff(), 1e-12 * scale);
}

TEST(TcnStreaming, EqualsNaiveFullWindowConvolutionWithProjection) {
  expect_streaming_equals_naive<Tcn<double, 4, 8, 3, 4, 2>>({4, 8, 3, 4, 2}, 11);
}

TEST(TcnStreaming, EqualsNaiveFullWindowConvolutionWithIdentitySkip) {
  expect_streaming_equals_naive<Tcn<double, 6, 6, 4, 3, 1>>({6, 6, 4, 3, 1}, 12);
}

TEST(TcnStreaming, EqualsNaiveWithOneLevelAndKernelTwo) {
  expect_streaming_equals_naive<Tcn<double, 3, 5, 1, 2, 1>>({3, 5, 1, 2, 1}, 15, 50);
}

TEST(TcnStreaming, DefaultPerJointShapeCoversWellOver70msAt400Hz) {
  using PerJoint = Tcn<double, 4, 32, 4>;
  EXPECT_EQ(PerJoint::kReceptiveField, 46);  // 1 + 3·(2⁴ − 1)
  EXPECT_EQ(PerJoint::kReceptiveField, offline::TcnArchitecture{}.receptive_field());
  EXPECT_GT(PerJoint::kReceptiveField / 400.0, 1.5 * 0.070);
  expect_streaming_equals_naive<PerJoint>({4, 32, 4, 4, 1}, 13, 100);
}

TEST(TcnStreaming, FiveLevelsSixtyFourChannelsEqualNaive) {
  using Wide = Tcn<double, 4, 64, 5>;
  EXPECT_EQ(Wide::kReceptiveField, 94);
  expect_streaming_equals_naive<Wide>({4, 64, 5, 4, 1}, 14, 40);
}

TEST(TcnStreaming, FloatEngineTracksDouble) {
  const FloatDeviation e = float_deviation<4, 16, 4>(21, 22, 200);
  EXPECT_LT(e.max_difference, 1e-4 * e.scale);
}

TEST(TcnStreaming, ShippedFloatNetworkEqualsDoubleToFloatRounding) {
  // The shipped shape (5 inputs, 16 channels, 4 levels, kernel 4): its taps may be summed in
  // separate accumulators (one per tap where the vector registers allow), so the float engine is
  // held to the rounding of float sums, a few ulps of the largest activation, not more.
  const FloatDeviation e = float_deviation<5, 16, 4>(23, 24, 300);
  ASSERT_GT(e.scale, 0.1);
  EXPECT_LT(e.max_difference, 3e-6 * e.scale);
}

TEST(TcnStreaming, OneRegisterHiddenVectorSumsByColumnsToFloatRounding) {
  // Four float channels fill one SSE register (16 floats one AVX-512 register, the shipped shape
  // natively): add_taps deals the columns to four accumulators (add_taps_by_columns). The same
  // network in double (per-tap sums) is the reference; the sums differ to float rounding only.
  const FloatDeviation e = float_deviation<5, 4, 4>(71, 72, 300);
  ASSERT_GT(e.scale, 0.1);
  EXPECT_LT(e.max_difference, 3e-6 * e.scale);
}

TEST(TcnStreaming, IsCausal) {
  const TcnArchitecture a{4, 8, 3, 4, 2};
  const offline::TcnParameters p = test::random_tcn_parameters(a, 31);
  Tcn<double, 4, 8, 3, 4, 2> one, two;
  test::load_parameters(p, one);
  test::load_parameters(p, two);
  const Eigen::MatrixXd raw = test::random_inputs(4, 120, 32);
  Eigen::MatrixXd changed = raw;
  const Eigen::Index change_at = 70;
  changed.col(change_at) += Eigen::Vector4d(5.0, -3.0, 2.0, 1.0);
  one.reset(raw.col(0));
  two.reset(raw.col(0));
  const Eigen::MatrixXd a_out = stream(one, raw, 0), b_out = stream(two, changed, 0);
  for (Eigen::Index t = 0; t < change_at; ++t)
    EXPECT_EQ(a_out.col(t), b_out.col(t)) << "t = " << t;
  EXPECT_GT((a_out.col(change_at) - b_out.col(change_at)).norm(), 1e-6);
  // … and the change is forgotten after the receptive field.
  const Eigen::Index forgotten = change_at + a.receptive_field();
  EXPECT_LT((a_out.rightCols(120 - forgotten) - b_out.rightCols(120 - forgotten)).norm(), 1e-12);
}

TEST(TcnStreaming, ResetEqualsFeedingTheSteadyInputForOneReceptiveField) {
  const TcnArchitecture a{4, 8, 3, 4, 2};
  const offline::TcnParameters p = test::random_tcn_parameters(a, 41);
  Tcn<double, 4, 8, 3, 4, 2> fed, prewarmed;
  test::load_parameters(p, fed);
  test::load_parameters(p, prewarmed);
  const Eigen::MatrixXd noise = test::random_inputs(4, 57, 42);  // leaves rings mid-way
  fed.reset(noise.col(0));
  for (Eigen::Index t = 0; t < noise.cols(); ++t)
    fed.step(noise.col(t));
  const Eigen::Vector4d steady(0.3, -0.2, 0.1, 0.05);
  for (int t = 0; t < a.receptive_field(); ++t)
    fed.step(steady);
  prewarmed.reset(steady);
  EXPECT_LT((fed.output() - prewarmed.output()).norm(), 1e-12);
  EXPECT_LT((fed.low() - prewarmed.low()).norm(), 1e-12);
  const Eigen::MatrixXd after = test::random_inputs(4, 80, 43);
  const Eigen::MatrixXd fo = stream(fed, after, 0), po = stream(prewarmed, after, 0);
  EXPECT_LT((fo - po).cwiseAbs().maxCoeff(), 1e-12);
}

/// A network given new weights mid-stream starts over as one built with them, in every kernel the
/// CPU runs (16 floats fill the x86 kernels' registers): the old network's activations, in its
/// rings and the kernels' pending sums, do not reach the new one's outputs.
TEST(TcnStreaming, NewWeightsStartOverAsANewNetwork) {
  const TcnArchitecture a{3, 16, 3, 4, 1};
  using Engine = Tcn<float, 3, 16, 3>;
  auto first = std::make_unique<Engine>(), second = std::make_unique<Engine>();
  test::load_parameters(test::random_tcn_parameters(a, 51), *first);
  test::load_parameters(test::random_tcn_parameters(a, 52), *second);
  const Eigen::MatrixXd before = test::random_inputs(3, 45, 53),
                        after = test::random_inputs(3, 60, 54);
  for (TcnKernel kernel : {TcnKernel::Portable, TcnKernel::Avx2, TcnKernel::Avx512}) {
    auto changed = std::make_unique<Engine>(first->weights());
    auto fresh = std::make_unique<Engine>(second->weights());
    if (!changed->use_kernel(kernel) || !fresh->use_kernel(kernel)) continue;
    stream(*changed, before, 0);
    changed->set_weights(second->weights());
    EXPECT_EQ(stream(*changed, after, 0), stream(*fresh, after, 0)) << int(kernel);
    changed->set_weights(first->weights());  // and prewarmed after the change
    const Eigen::Vector3f steady(0.2f, -0.1f, 0.4f);
    changed->reset(steady);
    auto prewarmed = std::make_unique<Engine>(first->weights());
    prewarmed->use_kernel(kernel);
    prewarmed->reset(steady);
    EXPECT_EQ(stream(*changed, after, 0), stream(*prewarmed, after, 0)) << int(kernel);
  }
}

TEST(TcnStreaming, NonFiniteSampleIsFlaggedAndHeldOver) {
  const offline::TcnParameters p = test::random_tcn_parameters({4, 8, 3, 4, 2}, 61);
  Tcn<double, 4, 8, 3, 4, 2> clean, dirty;
  test::load_parameters(p, clean);
  test::load_parameters(p, dirty);
  Eigen::MatrixXd raw = test::random_inputs(4, 60, 62);
  clean.reset(raw.col(0));
  dirty.reset(raw.col(0));
  Eigen::MatrixXd held = raw;
  held.col(30) = held.col(29);  // what the engine must substitute
  raw(1, 30) = std::numeric_limits<double>::quiet_NaN();
  const Eigen::MatrixXd a = stream(clean, held, 0), b = stream(dirty, raw, 0);
  EXPECT_EQ(a, b);
  EXPECT_EQ(dirty.skipped_inputs(), 1);
  EXPECT_EQ(clean.skipped_inputs(), 0);
}

TEST(TcnStreaming, StepAndResetAllocateNothing) {
  auto tcn = std::make_unique<Tcn<float, 4, 64, 5>>();
  test::load_parameters(test::random_tcn_parameters({4, 64, 5, 4, 1}, 51), *tcn);
  const Eigen::Vector4f x(0.1f, 0.2f, -0.3f, 0.0f);
  test::AllocationCounter counter;
  tcn->reset(x);
  float sum = 0.0f;
  for (int t = 0; t < 1000; ++t)
    sum += tcn->step(x * static_cast<float>(t % 7))(0);
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
}  // namespace tpf
