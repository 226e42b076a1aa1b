// The twin's plant: energy conservation with friction and control off, friction dissipates,
// holding still under stiction, payload adds gravity torque.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "offline/sim/scenario.hpp"
#include "offline/sim/twin_arm.hpp"
#include "offline/sim/twin_plant.hpp"
#include "support/constants.hpp"
#include "tpf/friction/friction_file.hpp"

namespace {

using tpf::test::kArm4Joints;

using namespace tpf::offline;

Scenario passive_scenario() {
  Scenario s = default_scenario(TPF_TEST_DATA_DIR "/arm4.robot.json");
  s.effects.friction = EffectsConfig::Friction::kNone;
  s.drive.enabled = false;
  return s;
}

TwinFriction twin_friction() {
  return load_twin_friction(TPF_TEST_DATA_DIR "/arm4.friction.json", kArm4Joints);
}

TEST(TwinPlant, EnergyIsConservedWithFrictionAndControlOff) {
  const Scenario s = passive_scenario();
  const TwinArm arm(s);
  TwinPlant plant(arm, twin_friction(), s.effects, 1.0 / s.inner_rate_hz);
  plant.reset(twin_vector({0.2, 0.5, -0.8, 0.4}), twin_vector({1.0, -0.5, 0.8, 1.5}));
  const double e0 = plant.energy();
  double max_kinetic = 0.0, max_drift = 0.0;
  for (int k = 0; k < 10 * 2000; ++k) {
    plant.step(TwinVector::Zero(kArm4Joints), TwinVector::Ones(kArm4Joints));
    max_drift = std::max(max_drift, std::abs(plant.energy() - e0));
    max_kinetic = std::max(max_kinetic,
                           plant.energy() - arm.energy(plant.q(), TwinVector::Zero(kArm4Joints)));
  }
  // The arm swings through large angles (kinetic energy of several J is exchanged with gravity).
  EXPECT_GT(max_kinetic, 1.0);
  EXPECT_LT(max_drift / std::abs(e0), 1e-6) << "E0 = " << e0;
  EXPECT_LT(max_drift / max_kinetic, 1e-6);
}

TEST(TwinPlant, FrictionDissipatesEnergyMonotonically) {
  Scenario s = passive_scenario();
  s.effects.friction = EffectsConfig::Friction::kLuGre;
  s.effects.gravity = false;
  const TwinArm arm(s);
  TwinPlant plant(arm, twin_friction(), s.effects, 1.0 / s.inner_rate_hz);
  plant.reset(TwinVector::Zero(kArm4Joints), twin_vector({1.0, -1.0, 1.5, -2.0}));
  double previous = plant.energy();
  for (int k = 0; k < 4000; ++k) {
    plant.step(TwinVector::Zero(kArm4Joints), TwinVector::Ones(kArm4Joints));
    // The bristles store a little energy (σ0 z²/2 ≤ τ_s²/2σ0 ≈ 2e-4 J), so allow that much rise.
    EXPECT_LE(plant.energy(), previous + 5e-4);
    previous = std::min(previous, plant.energy());
  }
  // Without gravity every joint comes to rest within 2 s.
  EXPECT_LT(plant.dq().cwiseAbs().maxCoeff(), 1e-3);
}

TEST(TwinPlant, StictionHoldsATorqueBelowBreakAwayAndYieldsAbove) {
  Scenario s = passive_scenario();
  s.effects.friction = EffectsConfig::Friction::kLuGre;
  s.effects.gravity = false;
  s.effects.load_dependent_friction = false;
  const auto friction = twin_friction();
  const TwinArm arm(s);
  for (double share : {0.8, 1.2}) {
    TwinPlant plant(arm, friction, s.effects, 1.0 / s.inner_rate_hz);
    plant.reset(TwinVector::Zero(kArm4Joints), TwinVector::Zero(kArm4Joints));
    // Ramp the torque up over 1 s (quasi-static), then hold it for 1 s.
    const double target = share * friction[0].stribeck.static_friction[0];
    TwinVector tau = TwinVector::Zero(kArm4Joints);
    for (int k = 0; k < 4000; ++k) {
      tau[0] = target * std::min(1.0, k / 2000.0);
      plant.step(tau, TwinVector::Ones(kArm4Joints));
    }
    if (share < 1.0) {
      // Only pre-sliding: quasi-statically dz/dx = 1 − σ0·z/τ_s, so holding 0.8·τ_s takes
      // x = −ln(0.2)·τ_s/σ0 ≈ 1.6·τ_s/σ0 (inertia and drift add a little).
      const double z_max =
          friction[0].stribeck.static_friction[0] / friction[0].bristle_stiffness[0];
      EXPECT_GT(std::abs(plant.q()[0]), 1.2 * z_max);
      EXPECT_LT(std::abs(plant.q()[0]), 2.5 * z_max);
      EXPECT_LT(std::abs(plant.dq()[0]), 1e-4);
      EXPECT_NEAR(plant.friction()[0], tau[0], 1e-3 * tau[0]);
    } else {
      EXPECT_GT(plant.q()[0], 0.05) << "above τ_s the joint breaks away and slides";
    }
  }
}

TEST(TwinArm, PayloadAddsItsGravityTorque) {
  Scenario s = passive_scenario();
  const TwinArm bare(s);
  s.effects.payload.enabled = true;
  s.effects.payload.mass = 0.5;
  s.effects.payload.position = tpf::Vector3<double>(0.1, 0.0, 0.0);
  const TwinArm loaded(s);
  const TwinVector q = twin_vector({0.1, 0.4, -0.6, 0.2});
  // The extra gravity torque is J_v(p)ᵀ·(−m·g) at the payload's world point.
  const TwinVector extra = loaded.gravity(q) - bare.gravity(q);
  // Use a pad-free check: finite difference of the payload's potential energy m·g·z(q).
  const double h = 1e-6;
  for (int j = 0; j < kArm4Joints; ++j) {
    TwinVector a = q, b = q;
    a[j] += h;
    b[j] -= h;
    const double dv = (loaded.energy(a, TwinVector::Zero(kArm4Joints)) -
                       bare.energy(a, TwinVector::Zero(kArm4Joints)) -
                       loaded.energy(b, TwinVector::Zero(kArm4Joints)) +
                       bare.energy(b, TwinVector::Zero(kArm4Joints))) /
                      (2 * h);
    EXPECT_NEAR(extra[j], dv, 1e-6);
  }
  EXPECT_GT(extra.cwiseAbs().maxCoeff(), 0.05);
}

// The passive arms of any joint count: energy kept without friction, and with friction the
// energy lost equals the work the friction torque did, Σ τ_f·Δq (bristle storage aside).
void expect_passive_energy_balance(const std::string& robot, const TwinVector& q0,
                                   const TwinVector& dq0) {
  Scenario s = default_scenario(robot);
  s.drive.enabled = false;
  s.effects.friction = EffectsConfig::Friction::kNone;
  const TwinArm arm(s);
  const TwinFriction friction = load_twin_friction(s.friction_file, arm.joints());
  TwinPlant free(arm, friction, s.effects, 1.0 / s.inner_rate_hz);
  free.reset(q0, dq0);
  const double e0 = free.energy();
  double drift = 0.0, swing = 0.0;
  const TwinVector zero = TwinVector::Zero(arm.joints()), ones = TwinVector::Ones(arm.joints());
  for (int k = 0; k < 2000; ++k) {
    free.step(zero, ones);
    drift = std::max(drift, std::abs(free.energy() - e0));
    swing = std::max(swing, free.energy() - arm.energy(free.q(), zero));
  }
  EXPECT_GT(swing, 0.1) << robot;  // J of kinetic energy exchanged with gravity
  EXPECT_LT(drift / swing, 1e-6) << robot;

  s.effects.friction = EffectsConfig::Friction::kLuGre;
  TwinPlant rubbing(arm, friction, s.effects, 1.0 / s.inner_rate_hz);
  rubbing.reset(q0, dq0);
  double work = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const TwinVector q = rubbing.q();
    rubbing.step(zero, ones);
    work += rubbing.friction().dot(rubbing.q() - q);
  }
  EXPECT_GT(work, 0.1) << robot;
  EXPECT_NEAR(e0 - rubbing.energy(), work, 0.02 * work) << robot;
}

TEST(TwinPlant, BenchPendulumKeepsOrLosesEnergyAsItShould) {
  expect_passive_energy_balance(TPF_TEST_DATA_DIR "/bench1.robot.json", twin_vector({1.2}),
                                twin_vector({0.0}));
}

TEST(TwinPlant, KinovaGen3KeepsOrLosesEnergyAsItShould) {
  expect_passive_energy_balance(TPF_TEST_DATA_DIR "/real/kinova-gen3/gen3.robot.json",
                                twin_vector({0.3, 0.8, -0.4, 1.2, 0.5, -0.7, 0.2}),
                                twin_vector({0.5, 0.0, -0.5, 0.3, 1.0, 0.0, 1.5}));
}

TEST(TwinPlant, NineJointArmKeepsOrLosesEnergyAsItShould) {
  expect_passive_energy_balance(TPF_SIM_TEST_DIR "/arm9/arm9.robot.json",
                                twin_vector({0.3, 0.8, -0.4, 1.2, 0.5, -0.7, 0.2, 0.9, -1.0}),
                                twin_vector({0.5, 0.0, -0.5, 0.3, 1.0, 0.0, 1.5, -1.0, 2.0}));
}

TEST(TwinArm, BenchGravityAndInertiaAreThePendulums) {
  const TwinArm arm(default_scenario(TPF_TEST_DATA_DIR "/bench1.robot.json"));
  ASSERT_EQ(arm.joints(), 1);
  // m = 1.5 kg at d = 0.25 m below the axis; I_yy = 0.03125; armature 5e-6·100² = 0.05 kg·m².
  for (double q : {-1.0, 0.4, 2.0}) {
    EXPECT_NEAR(arm.gravity(twin_vector({q}))[0], 1.5 * 9.81 * 0.25 * std::sin(q), 1e-12);
    EXPECT_NEAR(arm.mass_matrix(twin_vector({q}))(0, 0), 0.05 + 0.03125 + 1.5 * 0.0625, 1e-12);
  }
  EXPECT_DOUBLE_EQ(arm.torque_constant()[0], 5.0);
  EXPECT_DOUBLE_EQ(arm.current_limit()[0], 4.0);
  EXPECT_EQ(arm.pad_count(), 0);
}

}  // namespace
