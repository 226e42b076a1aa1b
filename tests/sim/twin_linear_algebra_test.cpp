// The twin's run-time-size linear algebra (twin_linear_algebra.hpp) gives Eigen's fixed-size
// results bit for bit for 1 to 8 unknowns (the twin's logs do not depend on how its vectors are
// sized), and solves correctly beyond (9 and 12 joints, where Eigen has no unrolled kernel).
#include "offline/sim/twin_linear_algebra.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cstring>
#include <random>
#include <string>

namespace {

using namespace tpf::offline;

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

// Counts the coefficients of `actual` whose bits differ from `expected`.
template <typename A, typename B>
int differing_bits(const A& expected, const B& actual) {
  int count = 0;
  for (Eigen::Index i = 0; i < expected.size(); ++i)
    count += !same_bits(expected[i], actual[i]);
  return count;
}

// A random symmetric positive definite matrix of size n with diagonal entries over three decades
// (a mass matrix with armature), the same for fixed and run-time sizes.
TwinMatrix random_spd_matrix(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TwinMatrix a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      a(i, j) = u(rng);
  TwinMatrix s = a * a.transpose() + 0.1 * TwinMatrix::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    const double scale = std::exp(3.0 * u(rng));
    s.row(i) *= std::sqrt(scale);
    s.col(i) *= std::sqrt(scale);
  }
  return s;
}

TwinVector random_twin_vector(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  TwinVector v(n);
  for (int i = 0; i < n; ++i)
    v[i] = u(rng);
  return v;
}

template <int N>
void expect_fixed_size_bits() {
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  std::mt19937_64 rng(100 + N);
  int cholesky = 0, ldlt = 0, jacobian = 0, transposed = 0, product = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const TwinMatrix s = random_spd_matrix(rng, N);
    const TwinVector b = random_twin_vector(rng, N);
    const Mat fixed = s;

    Eigen::LLT<Mat> llt(fixed);
    const Vec by_llt = llt.solve(Vec(b));
    TwinCholesky twin_cholesky;
    ASSERT_TRUE(twin_cholesky.compute(s));
    TwinVector x = b;
    twin_cholesky.solve_in_place(x);
    cholesky += differing_bits(by_llt, x) > 0;

    // With a semi-definite corner too: a zero row and column (a joint without inertia).
    TwinMatrix semi = s;
    if (N > 2 && trial % 4 == 0) {
      semi.row(1).setZero();
      semi.col(1).setZero();
    }
    const Vec by_ldlt = Mat(semi).ldlt().solve(Vec(b));
    TwinLdlt twin_ldlt;
    twin_ldlt.compute(semi);
    ldlt += differing_bits(by_ldlt, twin_ldlt.solve(b)) > 0;

    TwinJacobian j(3, N);
    for (int c = 0; c < N; ++c)
      j.col(c) = random_twin_vector(rng, 3);
    const Eigen::Matrix<double, 3, N> fixed_j = j;
    const tpf::Vector3<double> jx = fixed_j * Vec(b);
    jacobian += differing_bits(jx, multiply(j, b)) > 0;
    const tpf::Vector3<double> f = random_twin_vector(rng, 3);
    const Vec jtf = fixed_j.transpose() * f;
    transposed += differing_bits(jtf, multiply_transposed(j, f)) > 0;
    // A·x of the twin's plant is Eigen's product of small matrices sized at run time.
    using Small = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, N, N>;
    using SmallVec = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, N, 1>;
    const SmallVec sb = Small(s) * SmallVec(b);
    product += differing_bits(sb, multiply(s, b)) > 0;
  }
  const std::string at = " at N = " + std::to_string(N);
  EXPECT_EQ(cholesky, 0) << "Cholesky solves differing from Eigen::LLT" << at;
  EXPECT_EQ(ldlt, 0) << "LDLT solves differing from Eigen::LDLT" << at;
  EXPECT_EQ(jacobian, 0) << "J·x differing" << at;
  EXPECT_EQ(transposed, 0) << "Jᵀ·f differing" << at;
  EXPECT_EQ(product, 0) << "A·x differing" << at;
}

TEST(TwinLinearAlgebra, GivesEigensFixedSizeResultsBitForBit) {
#if defined(__FMA__)
  GTEST_SKIP() << "built with FMA (TPF_NATIVE): Eigen's fixed-size kernels fuse multiply-adds";
#else
  expect_fixed_size_bits<1>();
  expect_fixed_size_bits<2>();
  expect_fixed_size_bits<3>();
  expect_fixed_size_bits<4>();
  expect_fixed_size_bits<5>();
  expect_fixed_size_bits<6>();
  expect_fixed_size_bits<7>();
  expect_fixed_size_bits<8>();
#endif
}

TEST(TwinLinearAlgebra, SolvesAtAnySize) {
  std::mt19937_64 rng(7);
  for (int n : {1, 2, 9, 12, 20}) {
    const TwinMatrix s = random_spd_matrix(rng, n);
    const TwinVector b = random_twin_vector(rng, n);
    const TwinVector expected = s.llt().solve(b);
    const double scale = expected.norm();
    TwinCholesky cholesky;
    ASSERT_TRUE(cholesky.compute(s)) << n;
    TwinVector x = b;
    cholesky.solve_in_place(x);
    EXPECT_LT((x - expected).norm(), 1e-9 * scale) << n;
    TwinLdlt ldlt;
    ldlt.compute(s);
    EXPECT_LT((ldlt.solve(b) - expected).norm(), 1e-9 * scale) << n;

    TwinJacobian j(3, n);
    for (int c = 0; c < n; ++c)
      j.col(c) = random_twin_vector(rng, 3);
    const tpf::Vector3<double> f = random_twin_vector(rng, 3);
    EXPECT_LT((multiply(j, b) - j * b).norm(), 1e-13) << n;
    EXPECT_LT((multiply_transposed(j, f) - j.transpose() * f).norm(), 1e-13) << n;
    EXPECT_LT((multiply(s, b) - s * b).norm(), 1e-12 * s.norm()) << n;
  }
  TwinCholesky indefinite;
  EXPECT_FALSE(indefinite.compute(-TwinMatrix::Identity(9, 9)));
}

}  // namespace
