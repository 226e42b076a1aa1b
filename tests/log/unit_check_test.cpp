// A log read with the wrong units or kind must be flagged against the robot file's gravity
// torque, and a dead effort channel named. The log is written here (two files, motor side, no
// time) from a known pendulum: g(q) = 5·cos(q) N·m, gear ratio 50, motor K_t 0.08 N·m/A.
#include "offline/log/unit_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "log_test_files.hpp"
#include "offline/log/import_log.hpp"

namespace tpf::offline {
namespace {

using test::TempDir;
using test::write_text;

constexpr double kRatio = 50.0;
constexpr double kMotorKt = 0.08;  // N·m/A; the robot file's output-side K_t is 50 · 0.08 = 4
double gravity(double q) {
  return 5.0 * std::cos(q);
}

/// Rests of 1 s at poses where gravity changes size and sign, joined by 1 s cosine ramps.
double pose(double t) {
  const double rests[] = {1.2, -1.2, 2.0, 0.3, 1.2};
  const int k = std::min(static_cast<int>(t / 2.0), 3);
  const double s = std::clamp(t - 2.0 * k - 1.0, 0.0, 1.0);
  return rests[k] + (rests[k + 1] - rests[k]) * 0.5 * (1.0 - std::cos(std::numbers::pi * s));
}

/// Motor angle [rad] and motor torque [N·m] (= g/ratio at rest; inertia left out: the check
/// looks at rests only).
void write_pendulum(const TempDir& dir) {
  std::string positions = "enc\n", torques = "motor_torque\n";
  char line[64];
  for (int k = 0; k < 9000; ++k) {
    const double q = pose(k / 1000.0);
    std::snprintf(line, sizeof line, "%.17g\n", kRatio * q);
    positions += line;
    std::snprintf(line, sizeof line, "%.17g\n", gravity(q) / kRatio);
    torques += line;
  }
  write_text(dir / "positions.csv", positions);
  write_text(dir / "torques.csv", torques);
}

/// Imports the pendulum with the map's q unit and effort entry, and runs the checks with the
/// robot file's figures (ratio 50, K_t 4, limits ±2.5 rad).
LogChecks check(const TempDir& dir, const std::string& q_unit, const std::string& effort) {
  write_text(dir / "map.json",
             R"({"format": "tpf-import", "version": 1, "joints": 1, "rate_hz": 1000,
    "files": 2, "time": {"unit": "rate"}, "derive": {},
    "transmission": {"ratio": [50]},
    "columns": {"q": {"source": "enc", "side": "motor", "unit": ")" +
                 q_unit + R"("}, )" + effort + "}}");
  ImportReport report;
  const Log log = import_log({dir / "positions.csv", dir / "torques.csv"},
                             load_import_map(dir / "map.json"), report);
  UnitCheckInput in;
  in.t = log.col("t");
  in.q = log.col("q1");
  in.dq = log.col("dq1");
  in.ddq = log.col("ddq1");
  in.effort = log.col("tau1");
  in.gravity = in.q.unaryExpr([](double q) { return gravity(q); });
  in.gear_ratio = Eigen::VectorXd::Constant(1, kRatio);
  in.torque_constant = Eigen::VectorXd::Constant(1, kRatio * kMotorKt);
  in.lower = Eigen::VectorXd::Constant(1, -2.5);
  in.upper = Eigen::VectorXd::Constant(1, 2.5);
  return check_log_units(in);
}

const std::string kMotorTorque =
    R"("tau": {"source": "motor_torque", "unit": "N*m", "side": "motor"})";

TEST(UnitCheck, TheRightReadingPasses) {
  TempDir dir("unit_check");
  write_pendulum(dir);
  const LogChecks checks = check(dir, "rad", kMotorTorque);
  EXPECT_TRUE(checks.problems.empty()) << checks.problems.front();
  EXPECT_NEAR(checks.rest_factor[0], 1.0, 1e-3);
}

TEST(UnitCheck, MotorRadiansReadAsDegreesAreFlagged) {
  TempDir dir("unit_check");
  write_pendulum(dir);
  const LogChecks checks = check(dir, "deg", kMotorTorque);
  ASSERT_EQ(checks.problems.size(), 1u);
  EXPECT_NE(checks.problems[0].find("joint 1"), std::string::npos) << checks.problems[0];
  EXPECT_NE(checks.problems[0].find("q's units"), std::string::npos) << checks.problems[0];
}

TEST(UnitCheck, MotorTorqueReadAsAmperesIsFlaggedWithTheReadingThatFits) {
  TempDir dir("unit_check");
  write_pendulum(dir);
  const LogChecks checks = check(
      dir, "rad",
      R"("i": {"source": "motor_torque", "unit": "A", "side": "motor", "torque_constant": 0.08,
               "write": "torque"})");
  ASSERT_EQ(checks.problems.size(), 1u);
  EXPECT_NEAR(checks.rest_factor[0], kMotorKt, 1e-4);  // τ read = 50 · 0.08 · g/50
  EXPECT_NE(checks.problems[0].find("a motor torque in N*m read as a current in A"),
            std::string::npos)
      << checks.problems[0];
}

TEST(UnitCheck, AMotorSideTorqueLeftOnTheMotorSideIsFlagged) {
  TempDir dir("unit_check");
  write_pendulum(dir);
  const LogChecks checks = check(dir, "rad", R"("tau": {"source": "motor_torque", "unit": "N*m"})");
  ASSERT_EQ(checks.problems.size(), 1u);
  EXPECT_NEAR(checks.rest_factor[0], 1.0 / kRatio, 1e-5);
  EXPECT_NE(checks.problems[0].find("rests at 0.02x"), std::string::npos) << checks.problems[0];
  EXPECT_NE(checks.problems[0].find("is the effort motor-side torque"), std::string::npos);
}

TEST(UnitCheck, ADeadEffortChannelIsNamed) {
  UnitCheckInput in;
  const int n = 1000;
  in.t = Eigen::VectorXd::LinSpaced(n, 0.0, 9.99);
  in.q = in.t.array().sin().matrix();
  in.dq = in.t.array().cos().matrix();
  in.ddq = -in.q;
  in.effort = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < n; k += 10)
    in.effort(k, 0) = 0.01 * (k % 30);  // 93 % exact zeros, 3 values
  in.gravity = Eigen::VectorXd::Constant(n, 1.0);
  in.gear_ratio = Eigen::VectorXd::Ones(1);
  in.torque_constant = Eigen::VectorXd::Ones(1);
  in.lower = Eigen::VectorXd::Constant(1, -2.0);
  in.upper = Eigen::VectorXd::Constant(1, 2.0);
  const LogChecks checks = check_log_units(in);
  ASSERT_EQ(checks.dead_joints, std::vector<int>{1});
  EXPECT_NE(checks.problems.at(0).find("exactly 0 in 93 %"), std::string::npos)
      << checks.problems.at(0);
}

/// A swinging joint with no rest, its effort alive: only the limit and velocity checks speak.
UnitCheckInput swinging_joint() {
  UnitCheckInput in;
  const int n = 2000;
  in.t = Eigen::VectorXd::LinSpaced(n, 0.0, 1.999);
  in.q = (2.0 * in.t.array()).sin().matrix();
  in.dq = (2.0 * (2.0 * in.t.array()).cos()).matrix();
  in.ddq = -4.0 * in.q;
  in.effort = in.q + 0.1 * in.t;
  in.gravity = Eigen::VectorXd::Constant(n, std::nan(""));
  in.gear_ratio = Eigen::VectorXd::Constant(1, 100.0);
  in.torque_constant = Eigen::VectorXd::Ones(1);
  in.lower = Eigen::VectorXd::Constant(1, -2.0);
  in.upper = Eigen::VectorXd::Constant(1, 2.0);
  return in;
}

TEST(UnitCheck, VelocityInDegreesAgainstPositionInRadiansIsFlagged) {
  UnitCheckInput in = swinging_joint();
  EXPECT_TRUE(check_log_units(in).problems.empty());
  in.dq *= 180.0 / std::numbers::pi;
  const LogChecks checks = check_log_units(in);
  ASSERT_EQ(checks.problems.size(), 1u);
  EXPECT_NE(checks.problems[0].find("dq is 57.3x the difference quotient of q"), std::string::npos)
      << checks.problems[0];
}

TEST(UnitCheck, PositionsBeyondTheLimitsAreFlagged) {
  UnitCheckInput in = swinging_joint();
  in.upper[0] = 0.5;  // the swing reaches 1 rad
  const LogChecks checks = check_log_units(in);
  ASSERT_EQ(checks.problems.size(), 1u);
  EXPECT_NE(checks.problems[0].find("q outside the robot file's limits"), std::string::npos)
      << checks.problems[0];
}

/// A vertical lift (prismatic, m and m/s) that carries a constant 185 N: it rests for 2 s, then
/// moves at ±0.02 m/s (a lift's speed, below the rotary rest threshold of 0.05 rad/s) for 2 s,
/// where its drive pushes 185 ± 250 N against friction, and so on for 20 s.
UnitCheckInput lift_joint() {
  UnitCheckInput in;
  const int n = 2000;
  in.t = Eigen::VectorXd::LinSpaced(n, 0.0, 19.99);
  in.q.resize(n, 1);
  in.dq.resize(n, 1);
  in.ddq = Eigen::MatrixXd::Zero(n, 1);
  in.effort.resize(n, 1);
  double q = 0.1;
  for (int k = 0; k < n; ++k) {
    const int phase = static_cast<int>(in.t[k] / 2.0) % 4;  // rest, up, rest, down
    const double v = phase == 1 ? 0.02 : phase == 3 ? -0.02 : 0.0;
    q += v * 0.01;
    in.q(k, 0) = q, in.dq(k, 0) = v;
    in.effort(k, 0) = 185.0 + 250.0 * (v > 0 ? 1 : v < 0 ? -1 : 0) + 5.0 * std::sin(0.37 * k);
  }
  in.gravity = Eigen::MatrixXd::Constant(n, 1, 185.0);
  in.gear_ratio = Eigen::VectorXd::Ones(1);
  in.torque_constant = Eigen::VectorXd::Constant(1, 200.0);
  in.effort_is_current = true;
  in.lower = Eigen::VectorXd::Zero(1);
  in.upper = Eigen::VectorXd::Constant(1, 0.35);
  return in;
}

TEST(UnitCheck, APrismaticJointRestsBelowALinearThreshold) {
  UnitCheckInput in = lift_joint();
  // Read as revolute, 0.02 m/s passes for rest: the friction of the motion spoils the fit.
  const LogChecks rotary = check_log_units(in);
  ASSERT_EQ(rotary.problems.size(), 1u);
  EXPECT_NE(rotary.problems[0].find("does not follow the robot file's gravity"), std::string::npos)
      << rotary.problems[0];
  in.prismatic = {true};
  const LogChecks linear = check_log_units(in);
  EXPECT_TRUE(linear.problems.empty()) << linear.problems.front();
  EXPECT_NEAR(linear.rest_factor[0], 1.0, 1e-3);
}

TEST(UnitCheck, APrismaticJointBeyondItsLimitsIsFlaggedInMetres) {
  UnitCheckInput in = lift_joint();
  in.prismatic = {true};
  in.upper[0] = 0.05;  // the lift strokes between 0.1 and 0.14 m
  const LogChecks checks = check_log_units(in);
  ASSERT_EQ(checks.problems.size(), 1u);
  EXPECT_NE(checks.problems[0].find("limits [0, 0.05] m in"), std::string::npos)
      << checks.problems[0];
  EXPECT_EQ(checks.problems[0].find("rad"), std::string::npos) << checks.problems[0];
}

}  // namespace
}  // namespace tpf::offline
