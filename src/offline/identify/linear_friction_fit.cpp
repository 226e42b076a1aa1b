#include "offline/identify/linear_friction_fit.hpp"

#include <Eigen/Cholesky>
#include <limits>

namespace tpf::offline {

JointStribeck fit_linear_friction(const Eigen::VectorXd& dq, const Eigen::VectorXd& abs_gravity,
                                  const Eigen::VectorXd& target, bool fit_load, bool nonnegative) {
  const int columns = fit_load ? 4 : 2;  // sgn, q̇, sgn·|G|, q̇·|G|
  Eigen::Matrix4d gram = Eigen::Matrix4d::Zero();
  Eigen::Vector4d moment = Eigen::Vector4d::Zero();
  double target_square = 0;
  for (Eigen::Index i = 0; i < dq.size(); ++i) {
    const double sign = dq[i] > 0 ? 1.0 : (dq[i] < 0 ? -1.0 : 0.0);
    const Eigen::Vector4d row(sign, dq[i], sign * abs_gravity[i], dq[i] * abs_gravity[i]);
    gram.noalias() += row * row.transpose();
    moment += row * target[i];
    target_square += target[i] * target[i];
  }
  Eigen::Vector4d best = Eigen::Vector4d::Zero();
  double best_sse = target_square;  // the empty subset
  const int all = (1 << columns) - 1;
  for (int subset = nonnegative ? 1 : all; subset <= all; ++subset) {
    int used[4], n = 0;
    for (int c = 0; c < columns; ++c)
      if (subset & (1 << c)) used[n++] = c;
    Eigen::MatrixXd g(n, n);
    Eigen::VectorXd m(n);
    for (int a = 0; a < n; ++a) {
      m[a] = moment[used[a]];
      for (int b = 0; b < n; ++b)
        g(a, b) = gram(used[a], used[b]);
    }
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(g);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) continue;
    const Eigen::VectorXd x = ldlt.solve(m);
    if (!x.allFinite() || (nonnegative && (x.array() < 0).any())) continue;
    const double sse = target_square - 2 * x.dot(m) + x.dot(g * x);
    if (sse < best_sse) {
      best_sse = sse;
      best.setZero();
      for (int a = 0; a < n; ++a)
        best[used[a]] = x[a];
    }
  }
  JointStribeck out;
  out.coulomb = out.static_friction = best[0];
  out.viscous = best[1];
  out.load_coulomb = best[2];
  out.load_viscous = best[3];
  return out;
}

}  // namespace tpf::offline
