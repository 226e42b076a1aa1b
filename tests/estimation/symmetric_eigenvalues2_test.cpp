// The smaller eigenvalue of a symmetric 2×2 matrix: bit for bit Eigen's computeDirect, whose
// arithmetic it repeats, on random matrices of any scale and on the degenerate ones.
#include "tpf/common/symmetric_eigenvalues2.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <bit>
#include <cmath>
#include <cstdint>
#include <random>

namespace tpf::test {
namespace {

double eigen_smaller(double a, double b, double c) {
  Eigen::Matrix2d m;
  m << a, b, b, c;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver;
  solver.computeDirect(m, Eigen::EigenvaluesOnly);
  return solver.eigenvalues()[0];
}

TEST(SymmetricEigenvalues2, EqualsEigensComputeDirectBitForBit) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> exponent(-6.0, 6.0);
  for (int k = 0; k < 20000; ++k) {
    const double scale = std::pow(10.0, exponent(rng));
    double a = scale * normal(rng), b = scale * normal(rng), c = scale * normal(rng);
    if (k % 4 == 1) b *= 1e-9;  // nearly diagonal
    if (k % 4 == 2) c = a;      // equal diagonal
    if (k % 4 == 3) {           // a Gram matrix (positive semi-definite)
      const double x = normal(rng), y = normal(rng), z = normal(rng), w = normal(rng);
      a = scale * (x * x + y * y);
      b = scale * (x * z + y * w);
      c = scale * (z * z + w * w);
    }
    const double expected = eigen_smaller(a, b, c);
    const double got = smaller_symmetric_eigenvalue2(a, b, c);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(got), std::bit_cast<std::uint64_t>(expected))
        << k << ": " << a << " " << b << " " << c;
  }
}

TEST(SymmetricEigenvalues2, DegenerateMatrices) {
  EXPECT_EQ(smaller_symmetric_eigenvalue2(0.0, 0.0, 0.0), eigen_smaller(0.0, 0.0, 0.0));
  EXPECT_EQ(smaller_symmetric_eigenvalue2(2.0, 0.0, 2.0), 2.0);
  EXPECT_EQ(smaller_symmetric_eigenvalue2(3.0, 0.0, 1.0), 1.0);
  EXPECT_EQ(smaller_symmetric_eigenvalue2(1.0, 1.0, 1.0), eigen_smaller(1.0, 1.0, 1.0));
  EXPECT_TRUE(std::isnan(smaller_symmetric_eigenvalue2(1.0, std::nan(""), 1.0)));
  Matrix3<double> m;
  m << 4.0, 1.0, 9.0, 1.0, 2.0, 9.0, 9.0, 9.0, 9.0;
  EXPECT_EQ(smaller_symmetric_eigenvalue2(m), eigen_smaller(4.0, 1.0, 2.0));
}

}  // namespace
}  // namespace tpf::test
