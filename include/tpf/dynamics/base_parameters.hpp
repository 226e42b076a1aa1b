// Reduction of the regressor to identifiable base parameters.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace tpf {

/// The base (identifiable) parameters of a regressor: π_b = β π, with Y π = Y_b π_b for every
/// motion, where Y_b = Y.cols(independent). β = [1 K] Pᵀ from the column-pivoted QR of a stack of
/// regressors at random states (Gautier's numerical method): K = R11⁻¹ R12 expresses the
/// dependent columns through the independent ones. Start-up/offline code (dynamic sizes).
struct BaseParameters {
  std::vector<int> independent;  ///< columns of Y kept, ascending.
  Eigen::MatrixXd beta;          ///< b × p map from standard to base parameters.

  int size() const { return static_cast<int>(independent.size()); }
  /// Y_b = Y.cols(independent) (any row count).
  Eigen::MatrixXd reduce(const Eigen::MatrixXd& Y) const;
  /// π_b = β π.
  Eigen::VectorXd project(const Eigen::VectorXd& pi) const { return beta * pi; }
  /// Human-readable description of base parameter i as a combination of standard ones.
  std::string describe(int i, const std::vector<std::string>& column_names,
                       double tol = 1e-9) const;
};

/// Finds the base parameters from a stacked regressor W (rows = samples × joints, columns =
/// parameters), with rank tolerance `tol` relative to the largest |R_ii| of the unit-norm
/// columns. A column whose norm is at most `tol` times the largest column's is structurally zero
/// (rounding only): it is never a base parameter, and β gives it no weight.
BaseParameters find_base_parameters(const Eigen::MatrixXd& W, double tol = 1e-8);

}  // namespace tpf
