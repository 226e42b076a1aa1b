#include "offline/fit/gram_fit.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

namespace tpf::offline {

DesignGrams::DesignGrams(int joint_count, int feature_count)
    : joints(joint_count), features(feature_count) {
  blocks.assign(static_cast<std::size_t>(joints) * kRegimes * 2,
                Eigen::MatrixXd::Zero(features + 2, features + 2));
}

DesignGrams& DesignGrams::operator+=(const DesignGrams& other) {
  for (std::size_t i = 0; i < blocks.size(); ++i)
    blocks[i] += other.blocks[i];
  return *this;
}

namespace {

// Solves the equilibrated normal equations A x = b (complete orthogonal decomposition; a column
// that never appears, zero diagonal, stays zero).
Eigen::VectorXd solve_normal_equations(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const Eigen::Index m = A.rows();
  if (m == 0) return Eigen::VectorXd();  // no column to fit (Eigen's QR of 0×0 reads past it)
  Eigen::VectorXd d(m);
  for (Eigen::Index a = 0; a < m; ++a)
    d[a] = A(a, a) > 0 ? 1.0 / std::sqrt(A(a, a)) : 0.0;
  const Eigen::MatrixXd As = d.asDiagonal() * A * d.asDiagonal();
  // The threshold must be set before compute(): Eigen sizes Z by the rank found at compute time,
  // and a later, smaller threshold makes solve() read Z beyond it (uninitialised memory).
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(As.rows(), As.cols());
  cod.setThreshold(1e-11);
  cod.compute(As);
  return d.asDiagonal() * cod.solve(Eigen::VectorXd(d.asDiagonal() * b));
}

// The prior's term strength·s_c·(θ_c − mean_c)², s_c = A(c, c) of the data, on each fitted
// column c it holds: A(c, c) += strength·s_c, b_c += strength·s_c·mean_c.
void add_prior(const ColumnPrior& prior, const std::vector<int>& columns, Eigen::MatrixXd& A,
               Eigen::VectorXd& b) {
  if (!(prior.strength > 0)) return;
  for (std::size_t a = 0; a < columns.size(); ++a) {
    if (std::find(prior.columns.begin(), prior.columns.end(), columns[a]) == prior.columns.end())
      continue;
    const Eigen::Index i = static_cast<Eigen::Index>(a);
    const double weight = prior.strength * A(i, i);
    A(i, i) += weight;
    b[i] += weight * prior.mean[columns[a]];
  }
}

// Σ_j w_j Σ_r G over the selected training rows (and held-out ones, FitSelection::heldout_rows): A
// = Σφ_cφ_cᵀ, b = Σφ_c(y − φᵀθ_fixed).
void normal_equations(const DesignGrams& grams, const std::vector<int>& columns,
                      const Eigen::VectorXd* fixed, const FitSelection& selection,
                      Eigen::MatrixXd& A, Eigen::VectorXd& b) {
  const int p = grams.features;
  const int m = static_cast<int>(columns.size());
  A = Eigen::MatrixXd::Zero(m, m);
  b = Eigen::VectorXd::Zero(m);
  for (int j = 0; j < grams.joints; ++j) {
    const double w = selection.joint_weights.size() ? selection.joint_weights[j] : 1.0;
    for (int r = 0; r < DesignGrams::kRegimes; ++r) {
      if (!selection.regimes[r]) continue;
      Eigen::MatrixXd both;  // training + held-out rows, only for the final fit
      if (selection.heldout_rows) both = grams.at(j, r, 0) + grams.at(j, r, 1);
      const Eigen::MatrixXd& g = selection.heldout_rows ? both : grams.at(j, r, 0);
      for (int a = 0; a < m; ++a) {
        b[a] += w * g(columns[a], p);
        if (fixed) b[a] -= w * g.row(columns[a]).head(p).dot(*fixed);
        for (int c = 0; c < m; ++c)
          A(a, c) += w * g(columns[a], columns[c]);
      }
    }
  }
  add_prior(selection.prior, columns, A, b);
}

}  // namespace

Eigen::VectorXd fit_columns(const DesignGrams& grams, const std::vector<int>& columns,
                            const FitSelection& selection) {
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  normal_equations(grams, columns, nullptr, selection, A, b);
  const Eigen::VectorXd x = solve_normal_equations(A, b);
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(grams.features);
  for (std::size_t a = 0; a < columns.size(); ++a)
    theta[columns[a]] = x[static_cast<Eigen::Index>(a)];
  return theta;
}

Eigen::VectorXd refit_columns(const DesignGrams& grams, const std::vector<int>& columns,
                              const Eigen::VectorXd& theta, const FitSelection& selection) {
  Eigen::VectorXd fixed = theta;
  for (int c : columns)
    fixed[c] = 0.0;
  Eigen::MatrixXd A;
  Eigen::VectorXd b;
  normal_equations(grams, columns, &fixed, selection, A, b);
  const Eigen::VectorXd x = solve_normal_equations(A, b);
  for (std::size_t a = 0; a < columns.size(); ++a)
    fixed[columns[a]] = x[static_cast<Eigen::Index>(a)];
  return fixed;
}

ResidualSums residual_sums(const DesignGrams& grams, const Eigen::VectorXd& theta, int joint,
                           int regime, int split) {
  const int p = grams.features;
  const Eigen::MatrixXd& g = grams.at(joint, regime, split);
  ResidualSums s;
  s.count = g(p + 1, p + 1);
  const auto G = g.topLeftCorner(p, p);
  s.sum_squares = std::max(0.0, theta.dot(G * theta) - 2.0 * theta.dot(g.col(p).head(p)) + g(p, p));
  s.sum = g(p, p + 1) - theta.dot(g.col(p + 1).head(p));
  return s;
}

double ResidualSums::rmse() const {
  return count > 0 ? std::sqrt(sum_squares / count) : std::numeric_limits<double>::quiet_NaN();
}
double ResidualSums::mean() const {
  return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
}
double ResidualSums::std() const {
  if (count <= 0) return std::numeric_limits<double>::quiet_NaN();
  const double m = mean();
  return std::sqrt(std::max(0.0, sum_squares / count - m * m));
}

Eigen::VectorXd moving_residual_weights(const DesignGrams& grams, const Eigen::VectorXd& theta) {
  Eigen::VectorXd weights(grams.joints);
  for (int j = 0; j < grams.joints; ++j) {
    ResidualSums moving, every;
    for (int r = 0; r < DesignGrams::kRegimes; ++r) {
      const ResidualSums sums = residual_sums(grams, theta, j, r, 0);
      every += sums;
      if (r > 0) moving += sums;
    }
    const double std = moving.count > 0 ? moving.std() : every.std();
    const double sigma = std::isfinite(std) ? std::max(std, 1e-9) : 1.0;
    weights[j] = 1.0 / (sigma * sigma);
  }
  return weights;
}

}  // namespace tpf::offline
