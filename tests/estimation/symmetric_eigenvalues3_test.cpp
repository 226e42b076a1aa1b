// The written-out 3×3 Jacobi eigenvalues the contact force reads its conditioning from, against
// Eigen's QR iteration (what it replaced) and a long-double reference, on the Gram matrices J·Jᵀ
// it sees: random, ill-conditioned, rank-deficient and with clustered eigenvalues.
#include "tpf/common/symmetric_eigenvalues3.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace tpf::test {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// Q·diag(λ)·Qᵀ, Q a random rotation.
Matrix3<double> with_eigenvalues(std::mt19937& rng, const Vector3<double>& lambda) {
  std::normal_distribution<double> normal;
  Matrix3<double> g;
  for (int i = 0; i < 9; ++i)
    g.data()[i] = normal(rng);
  const Matrix3<double> q = Eigen::HouseholderQR<Matrix3<double>>(g).householderQ();
  const Matrix3<double> a = q * lambda.asDiagonal() * q.transpose();
  return (a + a.transpose()) / 2;
}

/// Test matrices: Gram matrices of random 3×4 Jacobians (one singular value scaled down by up to
/// 1e-12, or the Jacobian of rank 2 or 1), and Q·diag(λ)·Qᵀ with λ_min from 1e-16·λ_max up,
/// with λ_min ≈ λ_mid and λ_mid ≈ λ_max to 1e-16 relative, scales 1e-3 … 1e3.
std::vector<Matrix3<double>> cases() {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Matrix3<double>> out;
  for (int k = 0; k < 6000; ++k) {
    Eigen::Matrix<double, 3, 4> j;
    for (int i = 0; i < 12; ++i)
      j.data()[i] = normal(rng);
    if (k % 3 > 0) {
      Eigen::JacobiSVD<Eigen::Matrix<double, 3, 4>> svd(j,
                                                        Eigen::ComputeFullU | Eigen::ComputeFullV);
      Vector3<double> s = svd.singularValues();
      s[2] *=
          k % 3 == 1 ? std::pow(10.0, -6.0 * unit(rng)) : (k % 12 == 2 ? 0.0 : 1e-6 * unit(rng));
      if (k % 24 == 5) s[1] = 0.0;  // rank 1
      j = svd.matrixU() * s.asDiagonal() * svd.matrixV().leftCols<3>().transpose();
    }
    out.push_back(std::pow(10.0, 6.0 * unit(rng) - 3.0) * j * j.transpose());
    const double top = std::pow(10.0, 6.0 * unit(rng) - 3.0);
    const double low = top * std::pow(10.0, -16.0 * unit(rng)), mid = top * unit(rng);
    const double close = 1.0 - std::pow(10.0, -16.0 * unit(rng));
    const Vector3<double> lambda = k % 3 == 0   ? Vector3<double>(low, mid, top)
                                   : k % 3 == 1 ? Vector3<double>(mid * close, mid, top)
                                                : Vector3<double>(low, top * close, top);
    out.push_back(with_eigenvalues(rng, lambda));
  }
  out.push_back(Matrix3<double>::Zero());
  out.push_back(Matrix3<double>::Identity());
  out.push_back(Vector3<double>(3.0, 1.0, 2.0).asDiagonal());
  return out;
}

TEST(SymmetricEigenvalues3, AgreesWithEigensSolverAndTheLongDoubleReference) {
  double worst_vs_eigen = 0, worst_vs_reference = 0, eigen_vs_reference = 0, worst_relative = 0;
  int relative_cases = 0;
  for (const Matrix3<double>& a : cases()) {
    const Vector3<double> lambda = symmetric_eigenvalues3(a);
    ASSERT_TRUE(lambda[0] <= lambda[1] && lambda[1] <= lambda[2]);
    const Eigen::SelfAdjointEigenSolver<Matrix3<double>> eigen(a, Eigen::EigenvaluesOnly);
    using LongMatrix = Eigen::Matrix<long double, 3, 3>;
    const Eigen::SelfAdjointEigenSolver<LongMatrix> exact(a.cast<long double>(),
                                                          Eigen::EigenvaluesOnly);
    const Vector3<double> reference = exact.eigenvalues().cast<double>();
    const double scale = std::max(reference.cwiseAbs().maxCoeff(), 1e-300);
    worst_vs_eigen =
        std::max(worst_vs_eigen, (lambda - eigen.eigenvalues()).cwiseAbs().maxCoeff() / scale);
    worst_vs_reference =
        std::max(worst_vs_reference, (lambda - reference).cwiseAbs().maxCoeff() / scale);
    eigen_vs_reference = std::max(eigen_vs_reference,
                                  (eigen.eigenvalues() - reference).cwiseAbs().maxCoeff() / scale);
    // Where the contact force's rank flag reads λ_min (inverse condition √(λ_min/λ_max) ≳ 0.02).
    if (reference[0] >= 4e-4 * reference[2]) {
      worst_relative = std::max(worst_relative, std::abs(lambda[0] - reference[0]) / reference[0]);
      ++relative_cases;
    }
  }
  EXPECT_LE(worst_vs_reference, 4 * kEps);   // measured ≈ 2.4 ε
  EXPECT_LE(eigen_vs_reference, 16 * kEps);  // Eigen's QR iteration, for comparison: ≈ 9 ε
  EXPECT_LE(worst_vs_eigen, 16 * kEps);
  EXPECT_LE(worst_relative, 1e-12);  // measured ≈ 3.5e-13
  EXPECT_GT(relative_cases, 1000);
}

/// The rotation that zeroes a_pq against the long-double angle θ = ½·atan(2a_pq/(a_qq − a_pp)),
/// |θ| ≤ π/4, on both sides of the series limit |a_pq| = kSeriesLimit·|a_qq − a_pp| (ratios
/// 1e-12 … 1e2) and at θ = ±π/4 (a_qq = a_pp): t, c and s to a few ε, and the rotated a_pq,
/// (c² − s²)·a_pq + s·c·(a_pp − a_qq), zero to rounding.
TEST(SymmetricEigenvalues3, JacobiRotationMatchesTheLongDoubleAngle) {
  using Long = long double;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  double worst = 0, worst_off_diagonal = 0;
  int small = 0, large = 0;
  for (int k = 0; k < 20000; ++k) {
    const bool right_angle = k % 100 == 0;
    const double d = right_angle ? 0.0 : (k % 2 ? 1.0 : -1.0) * std::pow(10.0, 4.0 * unit(rng) - 2);
    const double size = right_angle ? 1.0 : std::pow(10.0, 14.0 * unit(rng) - 12) * std::abs(d);
    const double apq = (k % 4 < 2 ? 1.0 : -1.0) * size;
    const PlaneRotation<double> r = jacobi_rotation(d, apq);
    const Long angle = 0.5L * std::atan(2.0L * apq / Long(d));  // d = +0: ±π/4
    const Long t = std::tan(angle), c = std::cos(angle), s = std::sin(angle);
    worst = std::max({worst, double(std::abs(r.t - t) / std::abs(t)), double(std::abs(r.c - c)),
                      double(std::abs(r.s - s) / std::abs(s))});
    const Long rotated = (Long(r.c) * r.c - Long(r.s) * r.s) * apq - Long(r.s) * r.c * d;
    worst_off_diagonal = std::max(worst_off_diagonal,
                                  double(std::abs(rotated)) / std::max(std::abs(apq), std::abs(d)));
    (std::abs(apq) <= kSeriesLimit * std::abs(d) ? small : large)++;
  }
  EXPECT_LE(worst, 4 * kEps);               // measured ≈ 1.7 ε (s), 1.2 ε (t, c)
  EXPECT_LE(worst_off_diagonal, 4 * kEps);  // measured ≈ 1.4 ε
  EXPECT_GT(small, 5000);
  EXPECT_GT(large, 5000);
}

TEST(SymmetricEigenvalues3, ExactOnDiagonalAndRankDeficientMatrices) {
  EXPECT_EQ(symmetric_eigenvalues3(Matrix3<double>::Zero().eval()), Vector3<double>::Zero());
  EXPECT_EQ(symmetric_eigenvalues3(Matrix3<double>(Vector3<double>(3, -1, 2).asDiagonal())),
            Vector3<double>(-1, 2, 3));
  // A rank-1 Gram matrix v·vᵀ: eigenvalues 0, 0, |v|².
  const Vector3<double> v(0.3, -1.2, 0.7);
  const Vector3<double> lambda = symmetric_eigenvalues3((v * v.transpose()).eval());
  EXPECT_NEAR(lambda[2], v.squaredNorm(), 4 * kEps * v.squaredNorm());
  EXPECT_LE(std::abs(lambda[0]) + std::abs(lambda[1]), 4 * kEps * v.squaredNorm());
}

TEST(SymmetricEigenvalues3, NonFiniteEntryGivesNonFiniteEigenvalues) {
  for (double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j) {
        Matrix3<double> a = Matrix3<double>::Identity();
        a(i, j) = a(j, i) = bad;
        EXPECT_FALSE(symmetric_eigenvalues3(a).allFinite()) << i << ", " << j;
      }
}

}  // namespace
}  // namespace tpf::test
