// The friction reference of a log with a joint torque sensor: effort − (τ_sensor + I_a·q̈) is the
// friction itself, in files where the sensor varies; elsewhere the rigid-body prediction stays.
#include "offline/identify/sensor_friction.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace tpf::offline {
namespace {

constexpr double kScale = 100.0;    // mA per N·m: K_t = 1000/kScale N·m/A
constexpr double kArmature = 0.5;   // kg·m²
constexpr double kCoulomb = 120.0;  // mA
constexpr double kViscous = 80.0;   // mA per rad/s

/// One joint, two 300-row files at 100 Hz: a sine motion, τ_sensor a load torque; the effort is
/// K·(τ_sensor + I_a·q̈) + friction. The second file's sensor reads 0 (flat).
Log sensor_log() {
  Log log;
  log.meta.set("rate_hz", "100");
  log.columns = {"t", "q1", "dq1", "ddq1", "i1", "tau_sensor1"};
  log.values.resize(600, 6);
  for (int k = 0; k < 600; ++k) {
    const double t = k / 100.0, w = 2.0;
    const double q = std::sin(w * t), dq = w * std::cos(w * t), ddq = -w * w * std::sin(w * t);
    const double load = 3.0 + std::cos(0.7 * t);
    const double friction = kCoulomb * (dq > 0 ? 1.0 : -1.0) + kViscous * dq;
    const double effort = kScale * (load + kArmature * ddq) + friction;
    log.values.row(k) << t, q, dq, ddq, effort, k < 300 ? load : 0.0;
  }
  log.file_starts = {0, 300};
  return log;
}

TEST(SensorFriction, ReferenceIsTheSensorWhereItVariesAndTheFitFindsTheFriction) {
  const Log log = sensor_log();
  const Eigen::VectorXd kt = Eigen::VectorXd::Constant(1, 1000.0 / kScale);
  const JointSamples s = extract_joint_samples(log, kt);  // effort in N·m
  const Eigen::MatrixXd rigid = Eigen::MatrixXd::Constant(600, 1, -7.0);
  const SensorFrictionReference r =
      sensor_friction_reference(log, s, Eigen::VectorXd::Constant(1, kArmature), rigid);
  ASSERT_TRUE(r.from_sensor[0]);
  for (int k = 0; k < 300; ++k)
    EXPECT_NEAR(r.reference(k, 0), log.values(k, 5) + kArmature * log.values(k, 3), 1e-9) << k;
  for (int k = 300; k < 600; ++k)
    EXPECT_TRUE(std::isnan(r.reference(k, 0))) << "flat sensor in file 2, row " << k;
  EXPECT_NEAR(r.coulomb[0], kCoulomb / kScale, 1e-8);  // N·m
  EXPECT_NEAR(r.viscous[0], kViscous / kScale, 1e-8);
  EXPECT_NE(r.note.find("joints 1"), std::string::npos) << r.note;

  // No sensor column: the rigid-body prediction is the reference, and the note says so.
  Log without = log;
  without.columns.pop_back();
  without.values.conservativeResize(600, 5);
  const SensorFrictionReference none = sensor_friction_reference(
      without, extract_joint_samples(without, kt), Eigen::VectorXd::Zero(1), rigid);
  EXPECT_FALSE(none.from_sensor[0]);
  EXPECT_EQ(none.reference, rigid);
  EXPECT_NE(none.note.find("no joint has a usable sensor"), std::string::npos);
}

}  // namespace
}  // namespace tpf::offline
