#include "offline/identify/sensor_friction.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "offline/log/torque_sensor.hpp"

namespace tpf::offline {
namespace {

bool sensor_friction_moving(const JointSamples& s, Eigen::Index k, int j) {
  const Regime r = s.regimes[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
  return r == Regime::StaticToKinetic || r == Regime::Moving;
}

}  // namespace

SensorFrictionReference sensor_friction_reference(const Log& log, const JointSamples& s,
                                                  const Eigen::VectorXd& armature,
                                                  const Eigen::MatrixXd& rigid) {
  const int joints = s.joints();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto sensors = torque_sensor_columns(log, joints);
  SensorFrictionReference out;
  out.reference = rigid;
  out.from_sensor.assign(static_cast<std::size_t>(joints), false);
  out.coulomb = Eigen::VectorXd::Constant(joints, nan);
  out.viscous = out.coulomb;
  std::string used;
  for (int j = 0; j < joints; ++j) {
    const int column = log.column(indexed_name("tau_sensor", j + 1));
    bool any = false;
    for (std::size_t f = 0; f < log.file_count() && column >= 0; ++f)
      any = any || sensor_usable(sensors, f, j);
    if (!any) continue;
    out.from_sensor[static_cast<std::size_t>(j)] = true;
    out.reference.col(j).setConstant(nan);
    Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
    Eigen::Vector2d b = Eigen::Vector2d::Zero();
    std::size_t count = 0;
    for (std::size_t f = 0; f < log.file_count(); ++f) {
      if (!sensor_usable(sensors, f, j)) continue;
      const auto [begin, end] = log.file_rows(f);
      for (Eigen::Index k = begin; k < end; ++k) {
        const double tau = log.values(k, column);
        if (!s.valid[static_cast<std::size_t>(k)] || !std::isfinite(tau)) continue;
        out.reference(k, j) = tau + armature[j] * s.ddq(k, j);
        if (!sensor_friction_moving(s, k, j)) continue;
        const Eigen::Vector2d phi(s.dq(k, j) > 0 ? 1.0 : -1.0, s.dq(k, j));
        A += phi * phi.transpose();
        b += phi * (s.effort(k, j) - out.reference(k, j));
        ++count;
      }
    }
    if (count >= 2 && A.determinant() > 0) {
      const Eigen::Vector2d theta = A.ldlt().solve(b);
      out.coulomb[j] = theta[0];
      out.viscous[j] = theta[1];
    }
    used += (used.empty() ? "" : ", ") + std::to_string(j + 1) + " (" + std::to_string(count) +
            " moving samples)";
  }
  out.note = used.empty() ? "friction from the torque sensor: no joint has a usable sensor; "
                            "the friction is fitted against the rigid-body prediction"
                          : "friction fitted against the torque sensor on joints " + used +
                                ": target K_t·i − (τ_sensor + I_a·q̈)";
  return out;
}

}  // namespace tpf::offline
