// The twin with coupled drives (a robot file's coupled_to): a 2-joint planar arm in a vertical
// plane whose motor 2 turns with q₂ + 0.5·q₁ (C = [1 0; 0.5 1]), written by the tests to a temp
// dir with its own URDF, robot and friction files.
//  (a) friction and drives off: the coupled arm conserves energy as the uncoupled one does, and
//      its mass matrix is the uncoupled one's with the rotors moved through C:
//      M_c − M = Cᵀ·diag(I_a)·C − diag(I_a);
//  (b) at a given state the plant's friction on the joints is Cᵀ·F(C·v): each motor's LuGre step
//      (and the memoryless Stribeck curve) of twin_friction evaluated by hand on its own velocity;
//  (c) end to end: 60 s of simulated excitation logs the joint torques tau<j> = Cᵀ·K_t·i with
//      gt_fric in N·m (at rest tau = G + gt_fric to the current's noise); identify with the
//      coupled robot file recovers each motor's Coulomb and viscous friction within 10 %, and
//      the same log fitted as if each motor drove its own joint is clearly worse on joint 2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "offline/identify/identify.hpp"
#include "offline/log/log_metadata.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "offline/sim/twin_arm.hpp"
#include "offline/sim/twin_friction.hpp"
#include "offline/sim/twin_plant.hpp"
#include "support/temp_dir.hpp"
#include "tpf/friction/lugre.hpp"
#include "tpf/model/load_robot.hpp"

namespace {

using namespace tpf::offline;
using tpf::test::TempDir;

constexpr double kCoupling = 0.5;  // motor 2 turns with q₂ + 0.5·q₁

// The planted friction per motor (output side, N·m, rad/s; planar.friction.json below): no load
// terms and a small Stribeck excess, so that a Coulomb + viscous line is the curve identify
// fits; stiff bristles (σ0 = 2e4 N·m/rad, 2e-5 rad of pre-sliding). With σ0 = 2e3 the memory
// tilts the fitted line by 10–20 % (Coulomb low, viscous high), in the uncoupled twin alike.
constexpr double kCoulomb[2] = {0.40, 0.25};
constexpr double kViscous[2] = {0.30, 0.20};

// Writes planar.urdf (a copy of the generator's planar2.urdf), planar.friction.json,
// planar_coupled.robot.json and planar.robot.json (the same drives without coupled_to) into `dir`.
void write_planar_files(const TempDir& dir) {
  // The independent generator's arm (tests/generator/planar2), its drives written here.
  std::filesystem::copy_file(std::filesystem::path(TPF_TEST_DATA_DIR).parent_path() /
                                 "tests/generator/planar2/planar2.urdf",
                             dir / "planar.urdf");
  std::ofstream(dir / "planar.friction.json") << R"({
  "effort_unit": "N*m",
  "coulomb": [0.40, 0.25], "static": [0.44, 0.275], "stribeck_velocity": [0.05, 0.06],
  "stribeck_exponent": [1.5, 1.5], "viscous": [0.30, 0.20],
  "load_coulomb": [0, 0], "load_viscous": [0, 0],
  "bristle_stiffness": [20000, 15000], "bristle_damping": [50, 40]
})";
  const auto robot = [](bool coupled) {
    return std::string(R"({"format": "tpf-robot", "version": 1, "name": "planar_twin",
  "urdf": "planar.urdf", "friction": "planar.friction.json", "joints": [
    {"name": "joint1", "gear_ratio": 100, "rotor_inertia": 1e-5, "torque_constant": 2.0,
     "current_limit": 20000},
    {"name": "joint2", "gear_ratio": 100, "rotor_inertia": 1e-5, "torque_constant": 2.0,
     "current_limit": 20000)") +
           (coupled ? R"(, "coupled_to": {"joint1": 0.5}})" : "}") + "]}";
  };
  std::ofstream(dir / "planar_coupled.robot.json") << robot(true);
  std::ofstream(dir / "planar.robot.json") << robot(false);
}

class CoupledTwin : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir("coupled_twin");
    write_planar_files(*dir_);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string file(const std::string& name) { return (*dir_ / name).string(); }
  static Scenario scenario(bool coupled) {
    return default_scenario(file(coupled ? "planar_coupled.robot.json" : "planar.robot.json"));
  }
  static TempDir* dir_;
};
TempDir* CoupledTwin::dir_ = nullptr;

TEST_F(CoupledTwin, ArmCarriesTheRotorsThroughTheCoupling) {
  const TwinArm coupled(scenario(true)), plain(scenario(false));
  ASSERT_TRUE(coupled.coupled());
  ASSERT_FALSE(plain.coupled());
  TwinMatrix c = TwinMatrix::Identity(2, 2);
  c(1, 0) = kCoupling;
  EXPECT_EQ(coupled.coupling(), c);
  const double armature = 1e-5 * 100 * 100;
  const TwinVector q = twin_vector({0.3, -0.7});
  const TwinMatrix difference = coupled.mass_matrix(q) - TwinMatrix(plain.mass_matrix(q));
  const TwinMatrix expected =
      armature * (c.transpose() * c - TwinMatrix::Identity(2, 2));  // diag(I_a) = I_a·1
  EXPECT_LT((difference - expected).cwiseAbs().maxCoeff(), 1e-12) << difference;
}

TEST_F(CoupledTwin, EnergyIsConservedWithFrictionAndDrivesOffAsWithoutCoupling) {
  for (const bool coupled : {false, true}) {
    Scenario s = scenario(coupled);
    s.effects.friction = EffectsConfig::Friction::kNone;
    const TwinArm arm(s);
    const TwinFriction none{std::vector<JointFriction>(2)};
    TwinPlant plant(arm, none, s.effects, 1.0 / s.inner_rate_hz);
    plant.reset(twin_vector({0.3, 0.5}), twin_vector({2.0, -3.0}));
    const double e0 = plant.energy();
    double max_drift = 0.0, max_kinetic = 0.0;
    for (int k = 0; k < 5 * 2000; ++k) {
      plant.step(TwinVector::Zero(2), TwinVector::Ones(2));
      max_drift = std::max(max_drift, std::abs(plant.energy() - e0));
      max_kinetic =
          std::max(max_kinetic, plant.energy() - arm.energy(plant.q(), TwinVector::Zero(2)));
    }
    // The arm swings through large angles, exchanging several J with gravity.
    EXPECT_GT(max_kinetic, 1.0) << "coupled " << coupled;
    EXPECT_LT(max_drift / max_kinetic, 1e-6) << "coupled " << coupled;
    EXPECT_EQ(plant.friction().cwiseAbs().maxCoeff(), 0.0);
  }
}

// The mean velocity of the last step: q moved by h·v (twin_plant.hpp, step 2).
TwinVector mean_velocity(const TwinPlant& plant, const TwinVector& q0, double h) {
  return (plant.q() - q0) / h;
}

TEST_F(CoupledTwin, FrictionActsOnTheMotorsVelocitiesThroughTheCoupling) {
  const TwinMatrix c = TwinArm(scenario(true)).coupling();
  for (const auto model : {EffectsConfig::Friction::kLuGre, EffectsConfig::Friction::kStribeck}) {
    Scenario s = scenario(true);
    s.effects.friction = model;
    s.effects.gravity = false;
    const TwinArm arm(s);
    const TwinFriction friction = load_twin_friction(s.friction_file, 2);
    const double h = 1.0 / s.inner_rate_hz;
    TwinPlant plant(arm, friction, s.effects, h);
    // Joint 1 forward and joint 2 back: motor 2 turns with q̇₂ + 0.5·q̇₁ = −0.3 + 0.4 = 0.1.
    const TwinVector q0 = twin_vector({0.2, -0.4});
    plant.reset(q0, twin_vector({0.8, -0.3}));
    plant.step(TwinVector::Zero(2), TwinVector::Ones(2));
    const TwinVector u = c * mean_velocity(plant, q0, h);  // the motors' velocities
    ASSERT_GT(u[1], 0.05);
    ASSERT_LT(u[1], 0.15);
    TwinVector expected_motor(2);
    for (int m = 0; m < 2; ++m) {
      const JointFriction& p = friction[m];
      if (model == EffectsConfig::Friction::kLuGre) {
        // Bristles relaxed by reset, advanced over h at the motor's velocity.
        const auto step = tpf::lugre_joint_step(p, 0, 0.0, u[m], 0.0, h);
        expected_motor[m] = step.torque;
        EXPECT_NEAR(plant.bristles()[m], step.z, 1e-9 * std::abs(step.z) + 1e-15);
      } else {
        expected_motor[m] = tpf::stribeck_level(p.stribeck, 0, u[m], 0.0) * std::tanh(u[m] / 1e-3) +
                            tpf::viscous_coefficient(p.stribeck, 0, 0.0) * u[m];
      }
    }
    const TwinVector expected_joint = c.transpose() * expected_motor;
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(plant.motor_friction()[j], expected_motor[j], 1e-6) << "motor " << j + 1;
      EXPECT_NEAR(plant.friction()[j], expected_joint[j], 1e-6) << "joint " << j + 1;
    }
    // Not the joint-wise friction: on joint 2's own velocity −0.3 the curve has the other sign.
    EXPECT_GT(plant.friction()[1], 0.0);
  }
}

// Held-out RMS of identify's residual per joint over the rows where joint 1 moves
// (|q̇₁| > 0.05 rad/s): there motor 2 turns whatever joint 2 does, and a fit that takes motor 2's
// friction on q̇₂ alone misses it (most where joint 2 stands still, rows a per-joint "moving"
// selection would leave out).
Eigen::Vector2d rms_while_joint1_moves(const Identification& id) {
  const JointSamples& s = id.samples;
  Eigen::Vector2d rms;
  for (int j = 0; j < 2; ++j) {
    double sse = 0;
    int n = 0;
    for (Eigen::Index k = 0; k < s.size(); ++k)
      if (s.valid[k] && s.heldout[k] && std::abs(s.dq(k, 0)) > 0.05 &&
          std::isfinite(id.residual(k, j))) {
        sse += id.residual(k, j) * id.residual(k, j);
        ++n;
      }
    EXPECT_GT(n, 1000) << "joint " << j + 1;
    rms[j] = std::sqrt(sse / std::max(n, 1));
  }
  return rms;
}

TEST_F(CoupledTwin, IdentifyRecoversTheCoupledMotorsFrictionFromASimulatedLog) {
  Scenario s = scenario(true);
  s.kind = Scenario::Kind::kExcitation;
  s.initial_q = twin_vector({0.3, 0.5});
  s.excitation.lower = twin_vector({-0.9, -0.9});
  s.excitation.upper = twin_vector({1.5, 1.9});
  s.excitation.speed_min = 0.1;  // rad/s: a wide speed range separates Coulomb from viscous
  s.excitation.speed_max = 1.5;
  const Log log = simulate_to_log(s, 3, 60.0);
  // A coupled robot's effort is the joints' torque Cᵀ·K_t·i (N·m), as identify reads it.
  EXPECT_EQ(log.effort_prefix(), "tau");
  EXPECT_FALSE(log.has("i1"));
  // A coupled robot's effort is the joints' torque Cᵀ·K_t·i (N·m), as identify reads it.

  const auto coupled_model =
      tpf::load_robot<double, Eigen::Dynamic>(file("planar_coupled.robot.json"));
  ASSERT_TRUE(coupled_model.coupled);
  IdentifyOptions options;
  options.fit_load_friction = false;  // none planted; on 60 s α_c|G| would trade with τ_c
  const Identification id = identify(log, coupled_model, options);
  const auto& f = id.nominal.friction;
  std::printf("identify (coupled): motor 1 τ_c %.4f b %.4f; motor 2 τ_c %.4f b %.4f\n",
              f.coulomb[0], f.viscous[0], f.coulomb[1], f.viscous[1]);
  // 10 % of the planted levels: the log has the drives' noise and quantisation, a derived q̈ and
  // friction with (little) memory; over seeds 1–8 the largest error was 7.4 % (8.6 % on 40 s).
  for (int m = 0; m < 2; ++m) {
    EXPECT_NEAR(f.coulomb[m], kCoulomb[m], 0.10 * kCoulomb[m]) << "motor " << m + 1;
    EXPECT_NEAR(f.viscous[m], kViscous[m], 0.10 * kViscous[m]) << "motor " << m + 1;
  }

  // The ground truth is in the log's units: at rest tau = G(q) + gt_fric (N·m, no contact),
  // to the current's noise (6 mA·K_t = 0.012 N·m per motor, through Cᵀ) and quantisation.
  const TwinArm arm(s);
  Eigen::Vector2d sq = Eigen::Vector2d::Zero();
  int rest = 0;
  for (Eigen::Index k = 0; k < log.rows(); ++k) {
    const TwinVector q = twin_vector({log.col("q1")(k), log.col("q2")(k)});
    if (log.col("dq1")(k) != 0.0 || log.col("dq2")(k) != 0.0) continue;
    const TwinVector g = arm.gravity(q);
    for (int j = 0; j < 2; ++j) {
      const std::string n = std::to_string(j + 1);
      const double e = log.col("tau" + n)(k) - g[j] - log.col("gt_fric" + n)(k);
      sq[j] += e * e;
    }
    ++rest;
  }
  ASSERT_GT(rest, 500);
  const Eigen::Vector2d rest_rms = (sq / rest).cwiseSqrt();
  std::printf("at rest, RMS of tau - G - gt_fric [N·m]: %.4f %.4f (%d rows)\n", rest_rms[0],
              rest_rms[1], rest);
  EXPECT_LT(rest_rms.maxCoeff(), 0.03);

  // The same log fitted as if each motor drove its own joint: clearly worse on joint 2.
  const auto plain_model = tpf::load_robot<double, Eigen::Dynamic>(file("planar.robot.json"));
  const Identification plain = identify(log, plain_model, options);
  const Eigen::Vector2d with = rms_while_joint1_moves(id), without = rms_while_joint1_moves(plain);
  std::printf(
      "held-out RMS while joint 1 moves [N·m]: coupled fit %.4f %.4f, uncoupled fit %.4f %.4f\n",
      with[0], with[1], without[0], without[1]);
  EXPECT_GT(without[1], 3.0 * with[1]);  // 6.2–15× over seeds 1–8
  const auto& g = plain.nominal.friction;
  std::printf("identify (uncoupled): motor 1 τ_c %.4f b %.4f; motor 2 τ_c %.4f b %.4f\n",
              g.coulomb[0], g.viscous[0], g.coulomb[1], g.viscous[1]);
}

}  // namespace
