// How far apart regressor columns are on the data, from their Gram matrix A (AᵢⱼΣ φᵢφⱼ): the
// principal angles that decide whether diagnose can tell a candidate from the model, or two
// candidates from each other.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace tpf::offline {

/// Rows `rows` and columns `cols` of A.
Eigen::MatrixXd gram_block(const Eigen::MatrixXd& A, const std::vector<int>& rows,
                           const std::vector<int>& cols);

/// X^power of a symmetric PSD matrix (directions without energy map to 0): power −½, or −1 for
/// the pseudo-inverse.
Eigen::MatrixXd symmetric_power(const Eigen::MatrixXd& X, double power);

/// Schur complement A_CC − A_CM A_MM⁺ A_MC: the Gram of c's columns with model's span projected
/// out (M equilibrated before the pseudo-inverse: columns of very different scales).
Eigen::MatrixXd projected_gram(const Eigen::MatrixXd& A, const std::vector<int>& model,
                               const std::vector<int>& c);

/// sin² of the smallest principal angle between span(c) and span(model) on the data.
double distinct_share(const Eigen::MatrixXd& A, const std::vector<int>& model,
                      const std::vector<int>& c);

/// cos² of the smallest principal angle between the parts of span(b) and span(c) outside
/// span(model).
double shared_share(const Eigen::MatrixXd& A, const std::vector<int>& model,
                    const std::vector<int>& b, const std::vector<int>& c);

}  // namespace tpf::offline
