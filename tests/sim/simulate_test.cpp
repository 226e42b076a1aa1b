// End-to-end runs of the twin: determinism by seed, log round trip, sensor resolution, the
// equation of motion at rest in the logged data (K_t·i = G + τ_f − τ_ext), contacts and pads,
// teaching in closed loop, undeclared effects; the same physics on the 1-joint bench and the
// 7-joint Kinova Gen3 without skin.
#include "offline/sim/simulate.hpp"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "offline/log/read_log.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/sensor_quantisation.hpp"
#include "offline/sim/twin_arm.hpp"
#include "support/constants.hpp"
#include "support/temp_dir.hpp"
#include "tpf/common/error.hpp"
#include "tpf/model/robot_description.hpp"

namespace {

using tpf::test::kArm4Joints;

using namespace tpf::offline;

Scenario scenario(const std::string& name) {
  return load_scenario(std::string(TPF_TEST_DATA_DIR "/scenarios/") + name);
}

// RMS of K_t·i − (G(q) + τ_f − τ_ext) over samples at rest, mA, per joint (any robot).
TwinVector rest_equation_error(const Log& log, const Scenario& s) {
  const TwinArm arm(s);  // the scenarios checked here carry no undeclared payload
  const int n = arm.joints();
  const tpf::RobotDescription robot = tpf::load_robot_description(s.robot_file);
  TwinVector sq = TwinVector::Zero(n), q(n), dq(n);
  long rest = 0;
  for (Eigen::Index k = 0; k < log.rows(); ++k) {
    for (int j = 0; j < n; ++j) {
      q[j] = log.col(indexed_name("q", j + 1))(k);
      dq[j] = log.col(indexed_name("dq", j + 1))(k);
    }
    if (dq.cwiseAbs().maxCoeff() > 0) continue;
    const TwinVector g = arm.gravity(q);
    for (int j = 0; j < n; ++j) {
      const double kt = robot.drives[static_cast<std::size_t>(j)].torque_constant;
      const double expected = (g[j] - log.col(indexed_name("gt_tau_ext", j + 1))(k)) / kt * 1000 +
                              log.col(indexed_name("gt_fric", j + 1))(k);
      const double e = log.col(indexed_name("i", j + 1))(k) - expected;
      sq[j] += e * e;
    }
    ++rest;
  }
  EXPECT_GT(rest, 100);
  return (sq / static_cast<double>(rest)).cwiseSqrt();
}

TEST(Simulate, SameSeedSameLogBitForBitOtherSeedDiffers) {
  const Scenario s = scenario("excitation.json");
  const Log a = simulate_to_log(s, 7, 4.0), b = simulate_to_log(s, 7, 4.0);
  ASSERT_EQ(a.values.rows(), b.values.rows());
  EXPECT_EQ(std::memcmp(a.values.data(), b.values.data(), a.values.size() * sizeof(double)), 0);
  const Log c = simulate_to_log(s, 8, 4.0);
  EXPECT_FALSE(c.values.rows() == a.values.rows() && c.values == a.values);
}

TEST(Simulate, LogWriteReadRoundTrip) {
  const Scenario s = scenario("static-contacts.json");
  const tpf::test::TempDir dir("twin_roundtrip");
  const auto path = dir / "roundtrip.csv";
  const auto summary = simulate_to_file(s, 3, 3.0, path);
  const Log written = simulate_to_log(s, 3, 3.0);
  const Log read = read_log(path);
  EXPECT_EQ(read.columns, written.columns);
  ASSERT_EQ(static_cast<std::size_t>(read.rows()), summary.rows);
  EXPECT_TRUE(read.values == written.values);  // shortest round-trip formatting: exact
  EXPECT_EQ(read.meta.get("source").value_or(""), "simulated (tpf digital twin)");
  EXPECT_EQ(read.meta.get("seed").value_or(""), "3");
  EXPECT_EQ(read.joint_count(), kArm4Joints);
  EXPECT_EQ(read.pad_count(), 11);
}

TEST(Simulate, SensorsReportAtHardwareResolutionWithGapsAndJitter) {
  Scenario s = scenario("excitation.json");
  s.sensors.drop_probability = 0.05;
  s.sensors.jitter_probability = 0.2;
  const Log log = simulate_to_log(s, 11, 5.0);
  const auto t = log.col("t");
  int gaps = 0, jittered = 0;
  for (Eigen::Index k = 1; k < log.rows(); ++k) {
    const double dt = t(k) - t(k - 1);
    ASSERT_GT(dt, 0.0);
    if (dt > 0.0045) ++gaps;
    if (std::abs(dt - 0.0025) > 3e-4 && dt < 0.0045) ++jittered;
  }
  EXPECT_GT(gaps, 40);       // ≈ 5 % of 2000 cycles
  EXPECT_GT(jittered, 100);  // ≈ 20 % moved by ±0.5 ms
  for (int j = 1; j <= kArm4Joints; ++j) {
    for (Eigen::Index k = 0; k < log.rows(); ++k) {
      const double q = log.col(indexed_name("q", j))(k) / kPositionStep;
      const double dq = log.col(indexed_name("dq", j))(k) / kVelocityStep;
      const double i = log.col(indexed_name("i", j))(k);
      ASSERT_NEAR(q, std::round(q), 1e-6);
      ASSERT_NEAR(dq, std::round(dq), 1e-6);
      ASSERT_EQ(i, std::round(i));
    }
  }
}

TEST(Simulate, ExcitationObeysTheEquationOfMotionAtRest) {
  const Scenario s = scenario("excitation.json");
  const Log log = simulate_to_log(s, 5, 10.0);
  const TwinVector error = rest_equation_error(log, s);
  // Noise 6 mA plus the drive's current loop lag and pre-sliding accelerations.
  EXPECT_LT(error.maxCoeff(), 25.0) << error.transpose();
  // The friction at rest is large and history-dependent: far from zero at many rest samples.
  const auto f = log.col("gt_fric2"), dq = log.col("dq2");
  int large = 0;
  for (Eigen::Index k = 0; k < log.rows(); ++k)
    if (dq(k) == 0 && std::abs(f(k)) > 100) ++large;
  EXPECT_GT(large, 100);
}

TEST(Simulate, StaticContactsPushPadsAndShowInCurrents) {
  const Scenario s = scenario("static-contacts.json");
  const Log log = simulate_to_log(s, 2, 12.0);
  const TwinVector error = rest_equation_error(log, s);
  EXPECT_LT(error.maxCoeff(), 25.0) << error.transpose();
  const auto contact = log.col("gt_contact");
  int pushed = 0, seen = 0;
  for (Eigen::Index k = 0; k < log.rows(); ++k) {
    const int pad = static_cast<int>(contact(k));
    if (pad == 0) continue;
    const double f = std::sqrt(std::pow(log.col("gt_fx")(k), 2) + std::pow(log.col("gt_fy")(k), 2) +
                               std::pow(log.col("gt_fz")(k), 2));
    if (f < 2.0) continue;
    ++pushed;
    if (log.col(indexed_name("p", pad))(k) > 1.0) ++seen;
    EXPECT_GT(log.col("gt_tau_ext2").cwiseAbs().maxCoeff(), 0.0);
  }
  EXPECT_GT(pushed, 400);
  EXPECT_GT(seen, 0.9 * pushed);  // the pressed pad reads its push (after its 15 ms lag)
}

TEST(Simulate, TeachingMovesTheArmByHand) {
  Scenario s = scenario("teaching.json");
  const Log log = simulate_to_log(s, 4, 12.0);
  const auto contact = log.col("gt_contact");
  EXPECT_GT((contact.array() > 0).cast<double>().mean(), 0.3);
  double travel = 0.0;
  for (int j = 2; j <= kArm4Joints; ++j) {
    const auto q = log.col(indexed_name("q", j));
    travel = std::max(travel, q.maxCoeff() - q.minCoeff());
  }
  EXPECT_GT(travel, 0.1) << "the admittance controller must follow the hand";
  EXPECT_TRUE(log.values.allFinite());
}

TEST(Simulate, UndeclaredEffectsShowUp) {
  Scenario s = scenario("excitation.json");
  s.effects.thermal.enabled = true;
  s.effects.thermal.heating_k_per_a2s = 2.0;
  s.effects.thermal.time_constant_s = 60.0;
  const Log hot = simulate_to_log(s, 6, 6.0);
  const auto temp = hot.col("temp2");
  EXPECT_GT(temp(temp.size() - 1), temp(0) + 1.0);
  // A spring on joint 1 (no gravity there) shifts the holding current by −k·(q − q0)/K_t.
  Scenario spring = scenario("excitation.json");
  spring.effects.spring.enabled = true;
  spring.effects.spring.stiffness = twin_vector({5.0, 0, 0, 0});
  const Log with = simulate_to_log(spring, 6, 6.0);
  const Log without = simulate_to_log(scenario("excitation.json"), 6, 6.0);
  double corr = 0;
  for (Eigen::Index k = 0; k < std::min(with.rows(), without.rows()); ++k)
    corr += (with.col("i1")(k) - without.col("i1")(k)) * with.col("q1")(k);
  EXPECT_GT(corr, 0.0);  // motor must add +k·q to hold against the spring
}

TEST(Simulate, RangeOutsideTheJointLimitsIsRefused) {
  Scenario s = scenario("excitation.json");
  s.excitation.lower[1] = 2.5;  // joint 2's limit is ±2.0 rad
  s.excitation.upper[1] = 3.0;
  try {
    simulate_to_log(s, 1, 0.1);
    FAIL() << "expected an error";
  } catch (const tpf::Error& e) {
    EXPECT_NE(std::string(e.what()).find("excitation.lower_rad[1]"), std::string::npos) << e.what();
  }
}

TEST(Simulate, BenchHoldsThePendulumsGravityTorqueAtRest) {
  const Scenario s = scenario("bench1-excitation.json");
  const Log log = simulate_to_log(s, 9, 8.0);
  EXPECT_EQ(log.joint_count(), 1);
  EXPECT_EQ(log.pad_count(), 0);
  EXPECT_EQ(log.meta.get("robot").value_or(""), "bench1");
  EXPECT_LT(rest_equation_error(log, s)[0], 25.0);
  // Independent of tpf's dynamics: 1.5 kg, centre of mass 0.25 m below a horizontal axis, so at
  // rest K_t·(i − i_fric) = m·g·d·sin q, with K_t = 5 N·m/A (data/bench1.*).
  const auto q = log.col("q1"), dq = log.col("dq1"), i = log.col("i1"), f = log.col("gt_fric1");
  double worst = 0.0, largest = 0.0;
  for (Eigen::Index k = 0; k < log.rows(); ++k) {
    if (dq(k) != 0.0) continue;
    const double gravity = 1.5 * 9.81 * 0.25 * std::sin(q(k));
    worst = std::max(worst, std::abs(5.0 * (i(k) - f(k)) / 1000.0 - gravity));
    largest = std::max(largest, std::abs(gravity));
  }
  EXPECT_GT(largest, 1.0);  // the excitation held the pendulum well away from hanging
  EXPECT_LT(worst, 0.25);   // N·m: 6 mA noise (0.03 N·m) and pre-sliding transients
}

TEST(Simulate, KinovaGen3WithoutSkinObeysTheEquationOfMotionAtRest) {
  const Scenario s = scenario("kinova-gen3-excitation.json");
  EXPECT_EQ(s.joints, 7);
  EXPECT_TRUE(s.pads_file.empty());
  const Log log = simulate_to_log(s, 10, 4.0);
  EXPECT_EQ(log.joint_count(), 7);
  EXPECT_EQ(log.pad_count(), 0);
  for (const std::string& c : log.columns)
    EXPECT_NE(c.rfind("p", 0) == 0 && c.size() > 1 && std::isdigit(c[1]), true) << c;
  const TwinVector error = rest_equation_error(log, s);
  EXPECT_LT(error.maxCoeff(), 25.0) << error.transpose();
  // The shoulder (joint 2) carries the arm: its holding current is large and of gravity's sign.
  EXPECT_GT(log.col("i2").cwiseAbs().maxCoeff(), 300.0);
}

TEST(Simulate, PerJointVectorsMustFitTheRobot) {
  const std::string dir = TPF_TEST_DATA_DIR "/scenarios/";
  try {
    load_scenario(dir + "excitation.json", TPF_TEST_DATA_DIR "/bench1.robot.json");
    FAIL() << "expected an error";
  } catch (const tpf::Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("excitation.json"), std::string::npos) << m;
    EXPECT_NE(m.find("initial_q: must be an array of 1 numbers"), std::string::npos) << m;
  }
  // Left out, they default per joint: the arm4's contact scenario keys are all present, so take
  // a scenario that names none and run it on the Kinova.
  const tpf::test::TempDir temp("generic_scenario");
  const auto path = temp / "generic.json";
  std::ofstream(path) << R"({"kind": "static-contacts", "duration_s": 1})";
  const Scenario k =
      load_scenario(path.string(), TPF_TEST_DATA_DIR "/real/kinova-gen3/gen3.robot.json");
  EXPECT_EQ(k.joints, 7);
  EXPECT_EQ(k.initial_q.size(), 7);
  EXPECT_EQ(k.excitation.lower.size(), 7);
  EXPECT_EQ(k.effects.coupling.matrix.rows(), 7);
}

TEST(Simulate, TeachingNeedsPads) {
  const tpf::test::TempDir dir("teaching_noskin");
  const auto path = dir / "teaching.json";
  std::ofstream(path) << R"({"kind": "teaching", "robot": ")" TPF_TEST_DATA_DIR
                         R"(/bench1.robot.json"})";
  try {
    load_scenario(path.string());
    FAIL() << "expected an error";
  } catch (const tpf::Error& e) {
    EXPECT_NE(std::string(e.what()).find("kind: teaching needs a robot with skin pads"),
              std::string::npos)
        << e.what();
  }
}

TEST(Simulate, InitialPoseOutsideTheJointLimitsIsRefused) {
  // A scenario edited in code (load_scenario refuses the file): was simulated from beyond the end
  // stop. arm4's joint 2 turns in [-2, 2] rad.
  Scenario s = default_scenario(TPF_TEST_DATA_DIR "/arm4.robot.json");
  s.initial_q[1] = 2.5;
  try {
    simulate_to_log(s, 1, 0.01);
    FAIL() << "expected an error";
  } catch (const tpf::Error& e) {
    EXPECT_EQ(std::string(e.what()), TPF_TEST_DATA_DIR
              "/arm4.robot.json: initial_q[1]: 2.5 rad is outside the limits of "
              "joint 2, [-2, 2] rad, of the robot " TPF_TEST_DATA_DIR "/arm4.robot.json");
  }
}

TEST(Simulate, FrictionNoneRunsWithoutAFrictionFile) {
  // Was: "friction: no friction file" although the scenario turns friction off.
  const tpf::test::TempDir dir("simulate_friction_none");
  std::ofstream(dir / "bench.robot.json") << R"({"format": "tpf-robot", "version": 1,
    "urdf": ")" TPF_TEST_DATA_DIR R"(/bench1.urdf", "joints": [{"name": "joint1",
    "gear_ratio": 100, "rotor_inertia": 5e-6, "torque_constant": 5, "current_limit": 4000}]})";
  std::ofstream(dir / "s.json") << R"({"kind": "excitation", "robot": "bench.robot.json",
    "effects": {"friction": "none"}})";
  const Scenario s = load_scenario((dir / "s.json").string());
  const Log log = simulate_to_log(s, 1, 0.05);
  ASSERT_GT(log.rows(), 10);
  EXPECT_EQ(log.col("gt_fric1").cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(log.meta.get("friction_file").value_or(""), "none (effects.friction)");
}

}  // namespace
