// The AVX2 float products of the training pass equal Eigen's float GEMM bit for bit, and the
// window pass through them equals the same pass through Eigen (the weights do not change).
#include "offline/compensator_training/float_gemm16.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "offline/compensator_training/tcn_window_model.hpp"
#include "tcn_test_support.hpp"

namespace tpf::offline {
namespace {

Eigen::MatrixXf random_float(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  return test::random_inputs(static_cast<int>(rows), cols, seed).cast<float>();
}

/// Bitwise equality (EXPECT_EQ on floats compares values; −0 and +0 must match too).
void expect_identical(const Eigen::MatrixXf& got, const Eigen::MatrixXf& eigen,
                      const std::string& what) {
  ASSERT_EQ(got.rows(), eigen.rows()) << what;
  ASSERT_EQ(got.cols(), eigen.cols()) << what;
  int differing = 0;
  for (Eigen::Index i = 0; i < got.size(); ++i)
    differing += std::memcmp(got.data() + i, eigen.data() + i, sizeof(float)) != 0;
  EXPECT_EQ(differing, 0) << what << ": " << differing << " of " << got.size()
                          << " elements differ, worst " << (got - eigen).cwiseAbs().maxCoeff();
}

std::vector<std::ptrdiff_t> identity_offsets(Eigen::Index k) {
  std::vector<std::ptrdiff_t> offset(static_cast<std::size_t>(k));
  for (Eigen::Index i = 0; i < k; ++i)
    offset[static_cast<std::size_t>(i)] = i;
  return offset;
}

// The shapes of the shipped per-joint network (5 inputs, K = 4: 20 and 64 stacked rows) and of
// a 4-input one (16), over the window widths of its levels and short tails (from 2 steps).
TEST(FloatGemm16, ProductsEqualEigensBitForBit) {
  if (!float_gemm16_available()) GTEST_SKIP() << "no AVX2 on this CPU";
  std::uint64_t seed = 900;
  for (Eigen::Index k : {16, 20, 64}) {
    const std::vector<std::ptrdiff_t> offset = identity_offsets(k);
    for (Eigen::Index n : {2, 3, 5, 256, 280, 292, 298}) {
      const std::string shape = "k " + std::to_string(k) + ", n " + std::to_string(n);
      const Eigen::MatrixXf a = random_float(16, k, ++seed), b = random_float(k, n, ++seed);
      const Eigen::MatrixXf c0 = random_float(16, n, ++seed), d = random_float(16, n, ++seed);

      Eigen::MatrixXf eigen = c0, got = c0;
      eigen.noalias() += a * b;
      float_gemm16_accumulate(a.data(), k, b.data(), offset.data(), k, n, got.data());
      expect_identical(got, eigen, "C += A·B, " + shape);

      Eigen::MatrixXf g(16, k);
      eigen.noalias() = d * b.transpose();
      float_gemm16_times_transpose(d.data(), b.data(), offset.data(), k, k, n, g.data());
      expect_identical(g, eigen, "G = D·Sᵀ, " + shape);

      if (k % 8 != 0) continue;  // Aᵀ·D is used for the 64 stacked rows of blocks 1…L−1
      const Eigen::MatrixXf at = a.transpose();
      Eigen::MatrixXf x(k, n);
      eigen.noalias() = a.transpose() * d;
      float_gemm16_transpose_times(at.data(), k, d.data(), n, x.data());
      expect_identical(x, eigen, "X = Aᵀ·D, " + shape);
    }
  }
}

// Reading the K lagged columns of a block input in place equals the products with the stacked
// copy (block 0: 5 inputs, d = 1; block 3: 16 inputs, d = 8).
TEST(FloatGemm16, LaggedColumnsEqualTheStackedCopy) {
  if (!float_gemm16_available()) GTEST_SKIP() << "no AVX2 on this CPU";
  const int kernel = 4;
  std::uint64_t seed = 950;
  for (const auto& [in, d] : {std::pair<Eigen::Index, Eigen::Index>{5, 1}, {16, 8}}) {
    const Eigen::Index n = 256, width = n + (kernel - 1) * d, k = kernel * in;
    const Eigen::MatrixXf x = random_float(in, width, ++seed), a = random_float(16, k, ++seed);
    const Eigen::MatrixXf dz = random_float(16, n, ++seed), c0 = random_float(16, n, ++seed);
    Eigen::MatrixXf stack(k, n);
    std::vector<std::ptrdiff_t> offset(static_cast<std::size_t>(k));
    for (int j = 0; j < kernel; ++j) {
      stack.middleRows(j * in, in) = x.middleCols((kernel - 1 - j) * d, n);
      for (Eigen::Index c = 0; c < in; ++c)
        offset[static_cast<std::size_t>(j * in + c)] = (kernel - 1 - j) * d * in + c;
    }
    const std::string shape = "C_in " + std::to_string(in) + ", d " + std::to_string(d);
    Eigen::MatrixXf eigen = c0, got = c0;
    eigen.noalias() += a * stack;
    float_gemm16_accumulate(a.data(), k, x.data(), offset.data(), in, n, got.data());
    expect_identical(got, eigen, "C += A·stack, " + shape);
    Eigen::MatrixXf g(16, k);
    eigen.noalias() = dz * stack.transpose();
    float_gemm16_times_transpose(dz.data(), x.data(), offset.data(), in, k, n, g.data());
    expect_identical(g, eigen, "G = D·stackᵀ, " + shape);
  }
}

TEST(FloatGemm16, ZeroSumsArePositiveZeroAsInEigen) {
  if (!float_gemm16_available()) GTEST_SKIP() << "no AVX2 on this CPU";
  const Eigen::MatrixXf a = -Eigen::MatrixXf::Zero(16, 8), d = Eigen::MatrixXf::Zero(16, 3);
  Eigen::MatrixXf x(8, 3), g(16, 8);
  const Eigen::MatrixXf at = a.transpose();
  float_gemm16_transpose_times(at.data(), 8, d.data(), 3, x.data());
  const Eigen::MatrixXf zeros = Eigen::MatrixXf::Zero(8, 3);
  const std::vector<std::ptrdiff_t> offset = identity_offsets(8);
  float_gemm16_times_transpose(d.data(), zeros.data(), offset.data(), 8, 8, 3, g.data());
  Eigen::MatrixXf eigen_x(8, 3);
  eigen_x.noalias() = a.transpose() * d;
  expect_identical(x, eigen_x, "zero sums");
  EXPECT_FALSE(std::signbit(g(0, 0)));
}

// The forward pass of the shipped shape (5 → 16, 4 levels, K = 4, 256 outputs) in float, through
// the AVX2 products, equals the same pass with every product in Eigen (the code path they
// replace), block by block, bit for bit; the backward products are the ones tested above.
TEST(FloatGemm16, WindowForwardEqualsTheEigenPass) {
  if (!float_gemm16_available()) GTEST_SKIP() << "no AVX2 on this CPU";
  const TcnArchitecture a{5, 16, 4, 4, 1};
  const TcnParameters p = test::random_tcn_parameters(a, 77);
  const Eigen::Index outputs = 256, width = a.receptive_field() - 1 + outputs;
  const Eigen::MatrixXf x = random_float(a.inputs, width, 78);
  const Eigen::MatrixXf low = random_float(1, outputs, 79), high = random_float(1, outputs, 80);
  BasicTcnWindowWorkspace<float> ws;
  BasicTcnParameters<float> g = zero_tcn_parameters(a).cast<float>();
  const double loss = tcn_window_loss(p.cast<float>(), x, low, high, 1.0, 1.0, ws, &g);
  EXPECT_GT(loss, 0.0);
  EXPECT_TRUE(std::isfinite(loss));
  const BasicTcnParameters<float> pf = p.cast<float>();
  Eigen::MatrixXf act = x;
  for (int l = 0; l < a.levels; ++l) {
    const auto& b = pf.blocks[static_cast<std::size_t>(l)];
    const int d = a.dilation(l);
    const Eigen::Index in = act.rows(), t_out = act.cols() - (a.kernel - 1) * d;
    Eigen::MatrixXf stack(a.kernel * in, t_out), w(a.hidden, a.kernel * in);
    for (int j = 0; j < a.kernel; ++j) {
      stack.middleRows(j * in, in) = act.middleCols((a.kernel - 1 - j) * d, t_out);
      w.middleCols(j * in, in) = b.taps[static_cast<std::size_t>(j)];
    }
    Eigen::MatrixXf z;
    if (b.projection.size() > 0) {
      z.noalias() = b.projection * act.rightCols(t_out);
    } else {
      z = act.rightCols(t_out);
    }
    z.colwise() += b.bias;
    z.noalias() += w * stack;
    act = z.cwiseMax(0.0f);
    expect_identical(ws.activations[static_cast<std::size_t>(l + 1)], act,
                     "activations of block " + std::to_string(l));
  }
}

}  // namespace
}  // namespace tpf::offline
