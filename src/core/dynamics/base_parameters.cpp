#include "tpf/dynamics/base_parameters.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace tpf {

Eigen::MatrixXd BaseParameters::reduce(const Eigen::MatrixXd& Y) const {
  Eigen::MatrixXd Yb(Y.rows(), size());
  for (int i = 0; i < size(); ++i)
    Yb.col(i) = Y.col(independent[i]);
  return Yb;
}

std::string BaseParameters::describe(int i, const std::vector<std::string>& names,
                                     double tol) const {
  std::ostringstream out;
  bool first = true;
  for (Eigen::Index c = 0; c < beta.cols(); ++c) {
    const double v = beta(i, c);
    if (std::abs(v) <= tol) continue;
    if (!first)
      out << (v < 0 ? " - " : " + ");
    else if (v < 0)
      out << "-";
    if (std::abs(std::abs(v) - 1.0) > tol) out << std::abs(v) << "·";
    if (c < static_cast<Eigen::Index>(names.size()))
      out << names[c];
    else
      out << 'p' << c;
    first = false;
  }
  return out.str();
}

namespace {

/// Columns of `Ws` (unit or zero columns) kept as independent, ascending: pivoted Gram–Schmidt
/// taking, at each step, the column with the largest part outside the span of those kept so far,
/// until that part is at most `tol`. Columns whose parts are equal to within a relative 1e-6
/// count as tied and the lowest index wins: many regressor columns have equal norms (all are 1
/// here) or equal parts left, and a choice by their last bits would change the base set from one
/// build or regressor form to another.
std::vector<int> independent_columns(const Eigen::MatrixXd& Ws, double tol) {
  constexpr double kTie = 1e-6;
  Eigen::MatrixXd rest = Ws;
  std::vector<char> kept(static_cast<std::size_t>(Ws.cols()), 0);
  std::vector<int> columns;
  for (Eigen::Index step = 0; step < std::min(Ws.rows(), Ws.cols()); ++step) {
    double largest = 0.0;
    for (Eigen::Index c = 0; c < Ws.cols(); ++c)
      if (!kept[c]) largest = std::max(largest, rest.col(c).norm());
    if (!(largest > tol)) break;
    Eigen::Index pivot = 0;
    while (kept[pivot] || rest.col(pivot).norm() < (1.0 - kTie) * largest)
      ++pivot;
    const Eigen::VectorXd q = rest.col(pivot) / rest.col(pivot).norm();
    kept[pivot] = 1;
    columns.push_back(static_cast<int>(pivot));
    for (int pass = 0; pass < 2; ++pass)  // twice: orthogonal to rounding
      for (Eigen::Index c = 0; c < Ws.cols(); ++c)
        if (!kept[c]) rest.col(c) -= q * q.dot(rest.col(c));
  }
  std::sort(columns.begin(), columns.end());
  return columns;
}

}  // namespace

BaseParameters find_base_parameters(const Eigen::MatrixXd& W, double tol) {
  // Scale columns so that the rank decision does not depend on parameter units. A column whose
  // norm is at most `tol` times the largest is structurally zero (rounding of a term that
  // cancels, ~1e-14): scaled to unit norm it would look independent and become a base parameter
  // of ~1e14, so it is zeroed (unidentifiable) instead.
  Eigen::VectorXd scale = W.colwise().norm().transpose();
  const double largest = scale.size() > 0 ? scale.maxCoeff() : 0.0;
  for (Eigen::Index c = 0; c < scale.size(); ++c)
    scale(c) = scale(c) > tol * largest ? 1.0 / scale(c) : 0.0;
  const Eigen::MatrixXd Ws = W * scale.asDiagonal();

  const std::vector<int> independent = independent_columns(Ws, tol);
  std::vector<int> dependent;
  for (int c = 0; c < static_cast<int>(W.cols()); ++c)
    if (!std::binary_search(independent.begin(), independent.end(), c)) dependent.push_back(c);
  const int p = static_cast<int>(W.cols());
  const int b = static_cast<int>(independent.size());
  Eigen::MatrixXd Ws_ind(W.rows(), b), Ws_dep(W.rows(), p - b);
  for (int i = 0; i < b; ++i)
    Ws_ind.col(i) = Ws.col(independent[i]);
  for (int d = 0; d < p - b; ++d)
    Ws_dep.col(d) = Ws.col(dependent[d]);
  // Scaled columns: Ws_dep = Ws_ind · Ks  →  W_dep = W_ind · K, K = S_ind Ks S_dep⁻¹.
  const Eigen::MatrixXd Ks = Ws_ind.colPivHouseholderQr().solve(Ws_dep);

  BaseParameters base;
  base.independent = independent;
  base.beta = Eigen::MatrixXd::Zero(b, p);
  for (int r = 0; r < b; ++r) {
    const int col = independent[r];
    base.beta(r, col) = 1.0;
    for (int d = 0; d < p - b; ++d) {
      const int dep = dependent[d];
      if (scale(dep) == 0.0) continue;  // a column that is identically zero: unidentifiable
      base.beta(r, dep) = scale(col) * Ks(r, d) / scale(dep);
    }
  }
  // Ws = W·diag(s) and Ws_dep = Ws_ind·Ks give W_dep = W_ind·K with K(i, d) = s_ind Ks(i, d) /
  // s_dep, so Y π = Y_ind (π_ind + K π_dep): π_b,i = π_ind,i + Σ_d K(i, d) π_dep,d.
  return base;
}

}  // namespace tpf
