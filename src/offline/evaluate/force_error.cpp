#include "offline/evaluate/force_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace tpf::offline {

ForceErrorStats force_error(const Eigen::MatrixXd& estimate, const Eigen::MatrixXd& truth,
                            const std::vector<Eigen::Index>& rows) {
  std::vector<double> magnitude, angle;
  double sum_vector = 0.0;
  for (const Eigen::Index k : rows) {
    const Eigen::Vector3d f = estimate.row(k).transpose(), g = truth.row(k).transpose();
    if (!f.allFinite() || !g.allFinite() || g.norm() == 0.0) continue;
    magnitude.push_back(f.norm() - g.norm());
    const double c = f.norm() > 0 ? std::clamp(f.dot(g) / (f.norm() * g.norm()), -1.0, 1.0) : -1.0;
    angle.push_back(std::acos(c) * 180.0 / std::numbers::pi);
    sum_vector += (f - g).squaredNorm();
  }
  ForceErrorStats s;
  s.count = magnitude.size();
  const auto n = static_cast<Eigen::Index>(s.count);
  s.magnitude_error = Eigen::Map<Eigen::VectorXd>(magnitude.data(), n);
  s.angle_deg = Eigen::Map<Eigen::VectorXd>(angle.data(), n);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (n == 0) {
    s.magnitude_rmse = s.vector_rmse = s.median_angle_deg = s.p90_angle_deg = nan;
    return s;
  }
  s.magnitude_rmse = std::sqrt(s.magnitude_error.squaredNorm() / double(n));
  s.vector_rmse = std::sqrt(sum_vector / double(n));
  std::sort(angle.begin(), angle.end());
  const auto at = [&](double q) {
    return angle[static_cast<std::size_t>(std::lround(q * double(n - 1)))];
  };
  s.median_angle_deg = at(0.5);
  s.p90_angle_deg = at(0.9);
  return s;
}

}  // namespace tpf::offline
