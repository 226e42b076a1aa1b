// Contact-force error against ground truth: magnitude and direction.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace tpf::offline {

struct ForceErrorStats {
  std::size_t count = 0;
  Eigen::VectorXd magnitude_error;  ///< |F̂| − |F| per row [N]
  Eigen::VectorXd angle_deg;        ///< ∠(F̂, F) per row [°] (180 when F̂ = 0)
  double magnitude_rmse = 0.0;      ///< √mean((|F̂| − |F|)²) [N]
  double vector_rmse = 0.0;         ///< √mean(|F̂ − F|²) [N]
  double median_angle_deg = 0.0;
  double p90_angle_deg = 0.0;
};

/// Error of `estimate` against `truth` (both T × 3, same frame) over `rows`; rows where either is
/// not finite are skipped. NaN statistics when no row remains.
ForceErrorStats force_error(const Eigen::MatrixXd& estimate, const Eigen::MatrixXd& truth,
                            const std::vector<Eigen::Index>& rows);

}  // namespace tpf::offline
