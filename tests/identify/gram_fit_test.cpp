// Least squares from accumulated Gram matrices against the direct solution on the rows.
#include "offline/fit/gram_fit.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <random>

namespace tpf::test {
namespace {

using offline::DesignGrams;
using offline::FitSelection;

// Seeded rows φ (4 features) of one joint, y = φᵀθ + noise; static rows (regime 0) get an offset
// on feature 3 only, which is zero on the moving rows (regime 2), like the held friction.
struct Rows {
  Eigen::MatrixXd phi_moving, phi_static;
  Eigen::VectorXd y_moving, y_static;
};

Rows make_rows() {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Vector4d theta(1.5, -2.0, 0.5, 3.0);
  Rows r;
  r.phi_moving.resize(400, 4);
  r.phi_static.resize(300, 4);
  for (Eigen::Index k = 0; k < 400; ++k)
    r.phi_moving.row(k) << normal(rng), normal(rng), normal(rng), 0.0;
  for (Eigen::Index k = 0; k < 300; ++k)
    r.phi_static.row(k) << normal(rng), normal(rng), normal(rng), (k % 2 ? 1.0 : -1.0);
  r.y_moving = r.phi_moving * theta;
  r.y_static = r.phi_static * theta;
  for (Eigen::Index k = 0; k < 400; ++k)
    r.y_moving[k] += 0.1 * normal(rng);
  for (Eigen::Index k = 0; k < 300; ++k)
    r.y_static[k] += 0.5 * normal(rng);
  return r;
}

DesignGrams grams_of(const Rows& r) {
  DesignGrams g(1, 4);
  auto add = [&](const Eigen::MatrixXd& phi, const Eigen::VectorXd& y, int regime) {
    for (Eigen::Index k = 0; k < phi.rows(); ++k) {
      Eigen::VectorXd z(6);
      z << phi.row(k).transpose(), y[k], 1.0;
      g.at(0, regime, 0) += z * z.transpose();
    }
  };
  add(r.phi_moving, r.y_moving, 2);
  add(r.phi_static, r.y_static, 0);
  return g;
}

TEST(GramFit, FitColumnsEqualsDirectLeastSquaresOnTheSelectedRows) {
  const Rows r = make_rows();
  const DesignGrams g = grams_of(r);
  FitSelection moving;
  moving.regimes = {false, false, true};
  const Eigen::VectorXd theta = offline::fit_columns(g, {0, 1, 2}, moving);
  const Eigen::VectorXd direct = r.phi_moving.leftCols(3).colPivHouseholderQr().solve(r.y_moving);
  EXPECT_NEAR((theta.head(3) - direct).norm(), 0.0, 1e-10);
  EXPECT_EQ(theta[3], 0.0);  // not among the columns
  // The residual sums from the Gram equal those of the rows.
  const Eigen::VectorXd e = r.y_moving - r.phi_moving * theta;
  const auto sums = offline::residual_sums(g, theta, 0, 2, 0);
  EXPECT_NEAR(sums.sum_squares, e.squaredNorm(), 1e-8);
  EXPECT_NEAR(sums.sum, e.sum(), 1e-8);
  EXPECT_EQ(sums.count, 400.0);
}

TEST(GramFit, RefitColumnsFitsTheRestOnTheResidualAndKeepsTheOthers) {
  const Rows r = make_rows();
  const DesignGrams g = grams_of(r);
  FitSelection moving, at_rest;
  moving.regimes = {false, false, true};
  at_rest.regimes = {true, false, false};
  const Eigen::VectorXd theta = offline::fit_columns(g, {0, 1, 2}, moving);
  const Eigen::VectorXd refit = offline::refit_columns(g, {3}, theta, at_rest);
  EXPECT_EQ((refit.head(3) - theta.head(3)).norm(), 0.0);  // the motion fit is untouched
  const Eigen::VectorXd target = r.y_static - r.phi_static.leftCols(3) * theta.head(3);
  const double direct = r.phi_static.col(3).dot(target) / r.phi_static.col(3).squaredNorm();
  EXPECT_NEAR(refit[3], direct, 1e-10);
  EXPECT_NEAR(refit[3], 3.0, 0.1);  // the true held term
}

/// The prior's term μ·s_c·(θ_c − θ̄_c)² (s_c the column's own Σφ_c²): on columns 0–2 fitted
/// together, θ = (ΦᵀΦ + μS)⁻¹(Φᵀy + μSθ̄) with S = diag(ΦᵀΦ) on the prior's columns (1 and 2);
/// strength 0 is the plain fit, a very strong prior returns its mean.
TEST(GramFit, ColumnPriorAddsItsRelativeRidgeTowardItsMean) {
  const Rows r = make_rows();
  const DesignGrams g = grams_of(r);
  FitSelection moving;
  moving.regimes = {false, false, true};
  const Eigen::VectorXd plain = offline::fit_columns(g, {0, 1, 2}, moving);
  moving.prior.mean = Eigen::Vector4d(9.0, -1.0, 4.0, 7.0);
  moving.prior.columns = {1, 2, 3};
  EXPECT_EQ(offline::fit_columns(g, {0, 1, 2}, moving), plain);  // strength 0: no prior
  moving.prior.strength = 0.7;
  const Eigen::MatrixXd phi = r.phi_moving.leftCols(3);
  Eigen::MatrixXd A = phi.transpose() * phi;
  Eigen::VectorXd b = phi.transpose() * r.y_moving;
  for (int c : {1, 2}) {
    const double weight = 0.7 * A(c, c);
    A(c, c) += weight;
    b[c] += weight * moving.prior.mean[c];
  }
  const Eigen::VectorXd direct = A.colPivHouseholderQr().solve(b);
  const Eigen::VectorXd theta = offline::fit_columns(g, {0, 1, 2}, moving);
  EXPECT_NEAR((theta.head(3) - direct).norm(), 0.0, 1e-10);
  EXPECT_GT((theta - plain).norm(), 0.1);  // the prior moved it
  EXPECT_EQ(theta[3], 0.0);                // not fitted, whatever the prior says
  moving.prior.strength = 1e9;
  const Eigen::VectorXd held = offline::fit_columns(g, {0, 1, 2}, moving);
  EXPECT_NEAR(held[1], -1.0, 1e-6);
  EXPECT_NEAR(held[2], 4.0, 1e-6);
}

}  // namespace
}  // namespace tpf::test
