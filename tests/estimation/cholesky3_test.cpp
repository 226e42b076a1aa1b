// The written-out 3×3 Cholesky the contact force solves its normal equations with, against
// Eigen's LDLT (what it replaced) and the exact inverse: the same maths, so the same numbers to
// within what the matrix's condition allows.
#include "tpf/common/cholesky3.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace tpf::test {
namespace {

/// A random symmetric positive definite matrix Q·diag(λ)·Qᵀ with eigenvalues from 1 down to
/// 1/condition (log-uniform in between) and a random scale.
Matrix3<double> random_spd(std::mt19937& rng, double condition) {
  std::normal_distribution<double> normal;
  Matrix3<double> g;
  for (int i = 0; i < 9; ++i)
    g.data()[i] = normal(rng);
  const Matrix3<double> q = Eigen::HouseholderQR<Matrix3<double>>(g).householderQ();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double middle = std::pow(condition, -unit(rng));
  const double scale = std::pow(10.0, 6.0 * unit(rng) - 3.0);
  const Vector3<double> lambda = scale * Vector3<double>(1.0, middle, 1.0 / condition);
  return q * lambda.asDiagonal() * q.transpose();
}

TEST(Cholesky3, AgreesWithLdltToTheConditionsBound) {
  // Two backward-stable solves of A·x = b agree to about cond(A)·ε relative. Well conditioned
  // (cond ≤ 1e3, the contact force's usual case) that is far inside 1e-12; at cond 1e8 it is
  // still within 1e3·cond·ε.
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (double condition : {1.0, 10.0, 1e3, 1e5, 1e8}) {
    double worst_solve = 0, worst_diagonal = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const Matrix3<double> a = random_spd(rng, condition);
      const Vector3<double> b(normal(rng), normal(rng), normal(rng));
      const Cholesky3<double> cholesky(a);
      const Vector3<double> x = cholesky.solve(b);
      const Vector3<double> reference = a.ldlt().solve(b);
      worst_solve = std::max(worst_solve, (x - reference).norm() / reference.norm());
      const Vector3<double> diagonal = a.ldlt().solve(Matrix3<double>::Identity()).diagonal();
      worst_diagonal = std::max(
          worst_diagonal,
          (cholesky.inverse_diagonal() - diagonal).cwiseAbs().cwiseQuotient(diagonal).maxCoeff());
    }
    const double bound = std::max(1e-12, 1e3 * condition * std::numeric_limits<double>::epsilon());
    EXPECT_LT(worst_solve, condition <= 1e3 ? 1e-12 : bound) << "cond " << condition;
    EXPECT_LT(worst_diagonal, condition <= 1e3 ? 1e-12 : bound) << "cond " << condition;
  }
}

TEST(Cholesky3, SolvesAndInvertsAKnownMatrix) {
  // A = L·Lᵀ with L = [2 0 0; 1 3 0; −1 2 4]: A = [4 2 −2; 2 10 5; −2 5 21].
  Matrix3<double> a;
  a << 4, 2, -2, 2, 10, 5, -2, 5, 21;
  const Cholesky3<double> cholesky(a);
  const Vector3<double> x_true(1.0, -2.0, 0.5);
  EXPECT_LT((cholesky.solve(a * x_true) - x_true).norm(), 1e-14);
  const Vector3<double> diagonal = a.inverse().diagonal();
  EXPECT_LT((cholesky.inverse_diagonal() - diagonal).norm(), 1e-15);
}

TEST(Cholesky3, ReadsOnlyTheLowerTriangle) {
  Matrix3<double> a;
  a << 4, 2, -2, 2, 10, 5, -2, 5, 21;
  Matrix3<double> lower_only = a;
  lower_only(0, 1) = lower_only(0, 2) = lower_only(1, 2) = 99.0;
  const Vector3<double> b(0.3, -1.0, 2.0);
  EXPECT_EQ(Cholesky3<double>(a).solve(b), Cholesky3<double>(lower_only).solve(b));
}

TEST(Cholesky3, NotPositiveDefiniteGivesNoFiniteNumbers) {
  // An indefinite matrix: the documented contract is a non-finite result, never a plausible one.
  Matrix3<double> a;
  a << 1, 2, 0, 2, 1, 0, 0, 0, 1;
  const Vector3<double> x = Cholesky3<double>(a).solve(Vector3<double>(1, 1, 1));
  EXPECT_FALSE(x.allFinite());
}

}  // namespace
}  // namespace tpf::test
