#include "offline/diagnose/column_geometry.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace tpf::offline {

Eigen::MatrixXd gram_block(const Eigen::MatrixXd& A, const std::vector<int>& rows,
                           const std::vector<int>& cols) {
  Eigen::MatrixXd out(rows.size(), cols.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < cols.size(); ++c)
      out(r, c) = A(rows[r], cols[c]);
  return out;
}

Eigen::MatrixXd symmetric_power(const Eigen::MatrixXd& X, double power) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (X + X.transpose()));
  Eigen::VectorXd d = eig.eigenvalues();
  const double tol = 1e-12 * std::max(d.cwiseAbs().maxCoeff(), 1e-300);
  for (Eigen::Index i = 0; i < d.size(); ++i)
    d[i] = d[i] > tol ? std::pow(d[i], power) : 0.0;
  return eig.eigenvectors() * d.asDiagonal() * eig.eigenvectors().transpose();
}

Eigen::MatrixXd projected_gram(const Eigen::MatrixXd& A, const std::vector<int>& model,
                               const std::vector<int>& c) {
  if (model.empty()) return gram_block(A, c, c);
  Eigen::MatrixXd amm = gram_block(A, model, model);
  Eigen::VectorXd d(amm.rows());
  for (Eigen::Index i = 0; i < d.size(); ++i)
    d[i] = amm(i, i) > 0 ? 1.0 / std::sqrt(amm(i, i)) : 0.0;
  const Eigen::MatrixXd inv = d.asDiagonal() *
                              symmetric_power(d.asDiagonal() * amm * d.asDiagonal(), -1.0) *
                              d.asDiagonal();
  const Eigen::MatrixXd acm = gram_block(A, c, model);
  return gram_block(A, c, c) - acm * inv * acm.transpose();
}

double distinct_share(const Eigen::MatrixXd& A, const std::vector<int>& model,
                      const std::vector<int>& c) {
  const Eigen::MatrixXd r = symmetric_power(gram_block(A, c, c), -0.5);
  const Eigen::MatrixXd share = r * projected_gram(A, model, c) * r;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (share + share.transpose()));
  return std::clamp(eig.eigenvalues().minCoeff(), 0.0, 1.0);
}

double shared_share(const Eigen::MatrixXd& A, const std::vector<int>& model,
                    const std::vector<int>& b, const std::vector<int>& c) {
  std::vector<int> both = b;
  both.insert(both.end(), c.begin(), c.end());
  const Eigen::MatrixXd S = projected_gram(A, model, both);
  const Eigen::Index nb = static_cast<Eigen::Index>(b.size());
  const Eigen::Index nc = static_cast<Eigen::Index>(c.size());
  const Eigen::MatrixXd rb = symmetric_power(S.topLeftCorner(nb, nb), -0.5);
  const Eigen::MatrixXd rc = symmetric_power(S.bottomRightCorner(nc, nc), -0.5);
  const Eigen::MatrixXd cross = rb * S.topRightCorner(nb, nc) * rc;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(cross);
  const double top = svd.singularValues().size() ? svd.singularValues()[0] : 0.0;
  return std::clamp(top * top, 0.0, 1.0);
}

}  // namespace tpf::offline
