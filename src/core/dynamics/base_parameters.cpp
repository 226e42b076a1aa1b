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

BaseParameters find_base_parameters(const Eigen::MatrixXd& W, double tol) {
  // Scale columns so that the rank decision does not depend on parameter units.
  Eigen::VectorXd scale = W.colwise().norm().transpose();
  for (Eigen::Index c = 0; c < scale.size(); ++c)
    scale(c) = scale(c) > 0 ? 1.0 / scale(c) : 0.0;
  const Eigen::MatrixXd Ws = W * scale.asDiagonal();

  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Ws);
  qr.setThreshold(tol);
  const int p = static_cast<int>(W.cols());
  const int b = static_cast<int>(qr.rank());
  const Eigen::MatrixXd R = qr.matrixR().topRows(b).template triangularView<Eigen::Upper>();
  const auto& perm = qr.colsPermutation().indices();

  // Scaled columns: Ws_dep = Ws_ind · Ks  →  W_dep = W_ind · K, K = S_ind Ks S_dep⁻¹.
  const Eigen::MatrixXd R11 = R.leftCols(b);
  const Eigen::MatrixXd Ks = R11.template triangularView<Eigen::Upper>().solve(R.rightCols(p - b));

  BaseParameters base;
  std::vector<int> order(b);
  for (int i = 0; i < b; ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(), [&](int x, int y) { return perm(x) < perm(y); });
  base.beta = Eigen::MatrixXd::Zero(b, p);
  for (int r = 0; r < b; ++r) {
    const int i = order[r];  // row of R11 for the r-th kept column in ascending order
    const int col = perm(i);
    base.independent.push_back(col);
    base.beta(r, col) = 1.0;
    for (int d = 0; d < p - b; ++d) {
      const int dep = perm(b + d);
      if (scale(dep) == 0.0) continue;  // a column that is identically zero: unidentifiable
      base.beta(r, dep) = scale(col) * Ks(i, d) / scale(dep);
    }
  }
  // Ws = W·diag(s) and Ws_dep = Ws_ind·Ks give W_dep = W_ind·K with K(i, d) = s_ind Ks(i, d) /
  // s_dep, so Y π = Y_ind (π_ind + K π_dep): π_b,i = π_ind,i + Σ_d K(i, d) π_dep,d.
  return base;
}

}  // namespace tpf
