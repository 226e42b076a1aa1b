// The eigenvalues of a 3×N Jacobian's Gram matrix J·Jᵀ: the closed form where at most two columns
// are nonzero (a point on a link near the base) against a long-double reference, with the bounds
// of symmetric_eigenvalues3; the general path is symmetric_eigenvalues3's, bit for bit.
#include "tpf/common/gram_eigenvalues3.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace tpf::test {
namespace {

constexpr double kDoubleEpsilon = std::numeric_limits<double>::epsilon();
using Jacobian34 = Eigen::Matrix<double, 3, 4>;

/// Random 3×4 Jacobians with one or two nonzero columns, in any of the four places: the two
/// columns at any angle down to 1e-8 rad apart (nearly parallel), lengths 1e-3 … 1e3 apart, scales
/// 1e-3 … 1e3; a third of the two-column ones at right angles with equal lengths (λ_min = λ_max).
std::vector<Jacobian34> low_rank_jacobians() {
  std::mt19937 rng(17);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> column(0, 3);
  std::vector<Jacobian34> out;
  for (int k = 0; k < 6000; ++k) {
    const Vector3<double> a = Vector3<double>(normal(rng), normal(rng), normal(rng)).normalized();
    Vector3<double> n = a.cross(Vector3<double>(normal(rng), normal(rng), normal(rng)));
    n.normalize();
    const double angle =
        k % 3 == 2 ? std::numbers::pi / 2 : std::pow(10.0, -8.0 * unit(rng)) * std::numbers::pi / 2;
    const double length = k % 3 == 2 ? 1.0 : std::pow(10.0, 6.0 * unit(rng) - 3.0);
    const double scale = std::pow(10.0, 3.0 * unit(rng) - 1.5);
    Jacobian34 j = Jacobian34::Zero();
    const int first = column(rng);
    int second = column(rng);
    if (second == first) second = (first + 1) % 4;
    j.col(first) = scale * a;
    if (k % 7 != 0)  // else rank 1
      j.col(second) = scale * length * (std::cos(angle) * a + std::sin(angle) * n);
    out.push_back(j);
  }
  return out;
}

TEST(GramEigenvalues3, ClosedFormAgreesWithTheLongDoubleReference) {
  double worst = 0, worst_relative = 0, worst_zero = 0;
  int relative_cases = 0, rank_one_cases = 0;
  for (const Jacobian34& j : low_rank_jacobians()) {
    // The reference from the Gram of J's long-double entries: no rounding of G's own.
    const Eigen::Matrix<long double, 3, 4> jl = j.cast<long double>();
    const Eigen::Matrix<long double, 3, 3> gl = jl * jl.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<long double, 3, 3>> exact(
        gl, Eigen::EigenvaluesOnly);
    const Vector3<double> reference = exact.eigenvalues().cast<double>();
    const Matrix3<double> gram = j * j.transpose();
    const Vector3<double> lambda = gram_eigenvalues3(j, gram);
    ASSERT_TRUE(0 <= lambda[0] && lambda[0] <= lambda[1] && lambda[1] <= lambda[2]);
    EXPECT_EQ(lambda[0], 0.0);  // at most two nonzero columns: rank ≤ 2, exactly
    const double scale = reference.cwiseAbs().maxCoeff();
    worst = std::max(worst, (lambda - reference).cwiseAbs().maxCoeff() / scale);
    // The closed form's exact zero against iterating on G: the Jacobi's zero is rounding-level.
    worst_zero = std::max(worst_zero, std::abs(symmetric_eigenvalues3(gram)[0]) / scale);
    if (reference[1] >= 4e-4 * reference[2]) {
      worst_relative = std::max(worst_relative, std::abs(lambda[1] - reference[1]) / reference[1]);
      ++relative_cases;
    }
    if ((j.array() != 0).colwise().any().count() == 1) {
      ++rank_one_cases;
      EXPECT_EQ(lambda[1], 0.0);
    }
  }
  EXPECT_LE(worst, 4 * kDoubleEpsilon);       // symmetric_eigenvalues3's bound; measured ≈ 3.0 ε
  EXPECT_LE(worst_relative, 1e-12);           // measured ≈ 1.4e-15
  EXPECT_LE(worst_zero, 4 * kDoubleEpsilon);  // measured ≈ 1.2 ε
  EXPECT_GT(relative_cases, 1000);
  EXPECT_GT(rank_one_cases, 500);
}

TEST(GramEigenvalues3, ThreeOrMoreColumnsAreSymmetricEigenvalues3BitForBit) {
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  for (int k = 0; k < 200; ++k) {
    Jacobian34 j;
    for (int i = 0; i < 12; ++i)
      j.data()[i] = normal(rng);
    if (k % 2) j.col(k % 4).setZero();  // three nonzero columns
    const Matrix3<double> gram = j * j.transpose();
    EXPECT_EQ(gram_eigenvalues3(j, gram), symmetric_eigenvalues3(gram)) << k;
  }
}

TEST(GramEigenvalues3, ExactCases) {
  // Orthogonal columns of lengths 2 and 3 in places 1 and 3: eigenvalues 0, 4, 9.
  Jacobian34 j = Jacobian34::Zero();
  j.col(1) = Vector3<double>(0, 2, 0);
  j.col(3) = Vector3<double>(3, 0, 0);
  EXPECT_EQ(gram_eigenvalues3(j, (j * j.transpose()).eval()), Vector3<double>(0, 4, 9));
  // Parallel columns: rank 1, |a|² + |b|².
  j.col(1) = Vector3<double>(3, 0, 0);
  EXPECT_EQ(gram_eigenvalues3(j, (j * j.transpose()).eval()), Vector3<double>(0, 0, 18));
  EXPECT_EQ(gram_eigenvalues3(Jacobian34::Zero().eval(), Matrix3<double>::Zero().eval()),
            Vector3<double>::Zero());
}

TEST(GramEigenvalues3, NonFiniteEntryGivesNonFiniteEigenvalues) {
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    for (int nonzero : {1, 2, 4})
      for (int i = 0; i < 3; ++i) {
        Jacobian34 j = Jacobian34::Zero();
        j.leftCols(nonzero).setConstant(0.5);
        j(i, 0) = bad;
        EXPECT_FALSE(gram_eigenvalues3(j, (j * j.transpose()).eval()).allFinite())
            << bad << ", " << nonzero << ", " << i;
      }
}

}  // namespace
}  // namespace tpf::test
