#include "offline/diagnose/neighbour_load_choice.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <vector>

namespace tpf::offline {
namespace {

/// The energy of j's residual on `rows` that (|G_k| − mean)·[sgn q̇_j, q̇_j] removes.
double load_explained(const JointSamples& s, const Eigen::MatrixXd& residual,
                      const Eigen::MatrixXd& abs_gravity, const std::vector<Eigen::Index>& rows,
                      int j, int k) {
  double mean = 0;
  for (Eigen::Index i : rows)
    mean += abs_gravity(i, k);
  mean /= static_cast<double>(rows.size());
  Eigen::Matrix2d gram = Eigen::Matrix2d::Zero();
  Eigen::Vector2d rhs = Eigen::Vector2d::Zero();
  for (Eigen::Index i : rows) {
    const double load = abs_gravity(i, k) - mean;
    const Eigen::Vector2d x(load * (s.dq(i, j) > 0 ? 1.0 : -1.0), load * s.dq(i, j));
    if (!x.allFinite()) continue;
    gram += x * x.transpose();
    rhs += x * residual(i, j);
  }
  const Eigen::LDLT<Eigen::Matrix2d> ldlt(gram);
  if (ldlt.info() != Eigen::Success || !(gram.trace() > 0)) return 0.0;
  const double explained = rhs.dot(ldlt.solve(rhs));
  return std::isfinite(explained) ? explained : 0.0;
}

}  // namespace

Eigen::VectorXi choose_neighbour_loads(const JointSamples& s, const Eigen::MatrixXd& residual,
                                       const Eigen::MatrixXd& abs_gravity) {
  const int joints = static_cast<int>(residual.cols());
  Eigen::VectorXi source = Eigen::VectorXi::Constant(joints, -1);
  for (int j = 0; j < joints; ++j) {
    std::vector<Eigen::Index> rows;
    for (Eigen::Index k : moving_training_rows(s, j, 20000))
      if (std::isfinite(residual(k, j))) rows.push_back(k);
    if (rows.size() < 100) continue;
    double best = -1.0;
    for (int k = 0; k < joints; ++k)
      if (k != j) {
        const double explained = load_explained(s, residual, abs_gravity, rows, j, k);
        if (explained > best) {
          best = explained;
          source[j] = k;
        }
      }
  }
  return source;
}

}  // namespace tpf::offline
