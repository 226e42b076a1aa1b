#include "offline/evaluate/rest_memory.hpp"

#include <cmath>
#include <limits>

#include "offline/regimes/regime.hpp"

namespace tpf::offline {
namespace {

double above_floor(double rmse, double floor) {
  return std::sqrt(std::max(0.0, rmse * rmse - floor * floor));
}

}  // namespace

Eigen::VectorXd rest_noise_floor(const std::vector<ResidualRecording>& recordings,
                                 const RegimeOptions& options) {
  const Eigen::Index joints = recordings.empty() ? 0 : recordings.front().nominal.cols();
  Eigen::VectorXd floor(joints);
  for (Eigen::Index j = 0; j < joints; ++j) {
    double sum = 0.0;
    std::size_t pairs = 0;
    for (const ResidualRecording& r : recordings) {
      const Eigen::VectorXd dq = r.dq.col(j);
      const std::vector<Regime> regimes = label_regimes(r.t, dq, options);
      for (Eigen::Index k = 1; k < r.t.size(); ++k) {
        const double d = r.nominal(k, j) - r.nominal(k - 1, j);
        if (regimes[k] != Regime::Static || regimes[k - 1] != Regime::Static || !std::isfinite(d))
          continue;
        sum += d * d;
        ++pairs;
      }
    }
    floor[j] = pairs > 0 ? std::sqrt(sum / static_cast<double>(pairs) / 2.0)
                         : std::numeric_limits<double>::quiet_NaN();
  }
  return floor;
}

std::vector<RestMemoryRow> rest_memory(const std::vector<ResidualRow>& table,
                                       const Eigen::VectorXd& noise_floor) {
  std::vector<RestMemoryRow> rows;
  for (const ResidualRow& r : table) {
    if (r.joint < 0 || r.regime != Regime::Static || r.joint >= noise_floor.size()) continue;
    RestMemoryRow m;
    m.joint = r.joint;
    m.samples = r.nominal.count;
    m.nominal_rmse = r.nominal.rmse;
    m.compensated_rmse = r.compensated.rmse;
    m.noise_floor = noise_floor[r.joint];
    m.nominal_memory = above_floor(m.nominal_rmse, m.noise_floor);
    m.compensated_memory = above_floor(m.compensated_rmse, m.noise_floor);
    m.removed_share = m.nominal_memory > 0.0 ? 1.0 - m.compensated_memory / m.nominal_memory
                                             : std::numeric_limits<double>::quiet_NaN();
    m.nominal_times_floor = m.nominal_rmse / m.noise_floor;
    m.compensated_times_floor = m.compensated_rmse / m.noise_floor;
    rows.push_back(m);
  }
  return rows;
}

}  // namespace tpf::offline
