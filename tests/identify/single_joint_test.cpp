// A 1-joint arm logged with tau<j> (N·m): identification recovers the pendulum and its friction,
// and malformed logs fail with the file and line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "offline/identify/identify.hpp"
#include "offline/log/log_io.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

const std::string kRobot = std::string(TPF_TEST_SOURCE_DIR) + "/pendulum/pendulum.robot.json";
using V1 = JointVector<double, 1>;

// A synthetic torque log of the pendulum swinging through sines, with true friction and noise.
offline::Log pendulum_log(const StribeckParameters<double, 1>& friction) {
  const auto model = load_robot<double, 1>(kRobot);
  offline::Log log;
  log.source = "pendulum.csv";
  log.columns = {"t", "q1", "dq1", "ddq1", "tau1"};
  const int n = 40000;  // 100 s at 400 Hz
  log.values.resize(n, 5);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.01);
  Data<double, 1> data;
  for (int k = 0; k < n; ++k) {
    const double t = k / 400.0;
    const double w1 = 0.7, w2 = 1.9;
    const double q = 1.2 * std::sin(w1 * t) + 0.4 * std::sin(w2 * t + 1.0);
    const double dq = 1.2 * w1 * std::cos(w1 * t) + 0.4 * w2 * std::cos(w2 * t + 1.0);
    const double ddq = -1.2 * w1 * w1 * std::sin(w1 * t) - 0.4 * w2 * w2 * std::sin(w2 * t + 1.0);
    const double g = std::abs(compute_gravity(model, data, V1(q))[0]);
    const double tau = rnea(model, data, V1(q), V1(dq), V1(ddq))[0] +
                       stribeck_friction(friction, 0, dq, g) + noise(rng);
    log.values.row(k) << t, q, dq, ddq, tau;
  }
  return log;
}

TEST(SingleJoint, TorqueLogRecoversThePendulumAndItsFriction) {
  StribeckParameters<double, 1> truth;
  truth.coulomb << 0.3;
  truth.static_friction << 0.5;
  truth.stribeck_velocity << 0.1;
  truth.stribeck_exponent << 2.0;
  truth.viscous << 0.2;
  truth.load_coulomb << 0.02;
  const auto model = load_robot<double, 1>(kRobot);
  const offline::Identification id =
      offline::identify(pendulum_log(truth), load_robot<double, Eigen::Dynamic>(kRobot));
  EXPECT_EQ(id.samples.units.unit, EffortUnit::NewtonMetre);
  EXPECT_TRUE(id.consistency.consistent());
  const auto& f = id.nominal.friction;
  EXPECT_NEAR(f.coulomb[0], 0.3, 0.02);
  EXPECT_NEAR(f.static_friction[0], 0.5, 0.05);
  EXPECT_NEAR(f.viscous[0], 0.2, 0.01);
  EXPECT_NEAR(f.load_coulomb[0], 0.02, 0.005);
  // Held-out residual at the noise level (0.01 N·m).
  EXPECT_LT(id.heldout[0][offline::Regime::Moving].rmse, 0.015);
  // The rigid part equals the true RNEA (mass·g·l and inertia incl. armature).
  const NominalModel<double, 1> identified = joint_count_cast<1>(id.nominal);
  Data<double, 1> d1, d2;
  for (double q : {-1.0, 0.0, 0.7}) {
    V1 rigid, fric;
    predict_effort(identified, d1, V1(q), V1(0.3), V1(-2.0), rigid, fric);
    EXPECT_NEAR(rigid[0], rnea(model, d2, V1(q), V1(0.3), V1(-2.0))[0], 0.01);
  }
}

TEST(SingleJoint, MissingEffortShortAndTruncatedLogsAreRefusedWithTheFileName) {
  const auto model = load_robot<double, Eigen::Dynamic>(kRobot);
  offline::Log log = pendulum_log({});
  offline::Log no_effort = log;
  no_effort.columns[4] = "other";
  try {
    offline::identify(no_effort, model);
    FAIL() << "no effort column accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("pendulum.csv"), std::string::npos) << e.what();
  }
  offline::Log short_log = log;
  short_log.values.conservativeResize(50, Eigen::NoChange);
  try {
    offline::identify(short_log, model);
    FAIL() << "a 50-sample log accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("pendulum.csv: fewer than 100"), std::string::npos)
        << e.what();
  }
  // A log cut off mid-line: its cut row is left out and said, naming the file and the line.
  const auto path = std::filesystem::temp_directory_path() /
                    ("tpf_truncated_" + std::to_string(::getpid()) + ".csv");
  std::ofstream(path) << "# tpf-log: 1\nt,q1,dq1,tau1\n0,0,0,0\n0.0025,0,0,0\n0.005,0,";
  const offline::Log cut = offline::read_log(path);
  EXPECT_EQ(cut.rows(), 2);
  EXPECT_EQ(cut.quality.skipped_rows, 1u);
  ASSERT_EQ(cut.quality.notes.size(), 1u);
  EXPECT_NE(cut.quality.notes[0].find(path.string() + ":5"), std::string::npos)
      << cut.quality.notes[0];
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace tpf::test
