#include "offline/measured_study/sensor_residual.hpp"

#include <cmath>
#include <limits>

#include "offline/log/torque_sensor.hpp"
#include "offline/signal/causal_low_pass.hpp"

namespace tpf::offline {
namespace {
constexpr double kNoResidual = std::numeric_limits<double>::quiet_NaN();
}  // namespace

Eigen::MatrixXd sensor_residual(const SensorSide& side) {
  const Log& log = *side.log;
  const JointSamples& s = *side.samples;
  const int joints = s.joints();
  const auto sensors = torque_sensor_columns(log, joints);
  Eigen::MatrixXd r = Eigen::MatrixXd::Constant(s.size(), joints, kNoResidual);
  for (int j = 0; j < joints; ++j) {
    const int sensor = log.column(indexed_name("tau_sensor", j + 1));
    if (sensor < 0) continue;
    for (std::size_t f = 0; f < log.file_count(); ++f) {
      if (!sensor_usable(sensors, f, j)) continue;
      const auto [begin, end] = log.file_rows(f);
      for (Eigen::Index k = begin; k < end; ++k)
        if (s.valid[static_cast<std::size_t>(k)])
          r(k, j) = s.effort(k, j) - side.drive_loss(k, j) - log.values(k, sensor);
    }
  }
  return r;
}

Eigen::VectorXd sensor_shifted(const SensorSide& side, const Eigen::VectorXd& r, int j, int shift) {
  const Log& log = *side.log;
  const int sensor = log.column(indexed_name("tau_sensor", j + 1));
  Eigen::VectorXd out = Eigen::VectorXd::Constant(r.size(), kNoResidual);
  for (std::size_t f = 0; f < log.file_count(); ++f) {
    const auto [begin, end] = log.file_rows(f);
    for (Eigen::Index k = begin; k < end; ++k) {
      const Eigen::Index m = k + shift;
      if (m < begin || m >= end || !std::isfinite(r[k]) || !std::isfinite(r[m])) continue;
      out[k] = r[k] + log.values(k, sensor) - log.values(m, sensor);
    }
  }
  return out;
}

Eigen::VectorXd current_low_passed(const SensorSide& side, const Eigen::VectorXd& r, int j,
                                   double tau) {
  const JointSamples& s = *side.samples;
  const Eigen::VectorXd e = s.effort.col(j);
  return r + (causal_low_pass(s.t, e, tau, side.log->file_starts) - e);
}

}  // namespace tpf::offline
