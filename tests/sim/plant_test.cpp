// The twin's plant: energy conservation with friction and control off, friction dissipates,
// holding still under stiction, payload adds gravity torque.
#include <gtest/gtest.h>

#include <cmath>

#include "offline/sim/scenario.hpp"
#include "offline/sim/twin_arm.hpp"
#include "offline/sim/twin_plant.hpp"
#include "tpf/friction/friction_file.hpp"

namespace {

using namespace tpf::offline;

Scenario passive_scenario() {
  Scenario s;
  s.robot_file = TPF_TEST_DATA_DIR "/arm4.robot.json";
  s.pads_file = TPF_TEST_DATA_DIR "/arm4.pads.json";
  s.friction_file = TPF_TEST_DATA_DIR "/arm4.friction.json";
  s.effects.friction = EffectsConfig::Friction::kNone;
  s.drive.enabled = false;
  return s;
}

tpf::LuGreParameters<double, kTwinJoints> twin_friction() {
  return tpf::load_lugre_parameters<double, kTwinJoints>(TPF_TEST_DATA_DIR "/arm4.friction.json");
}

TEST(TwinPlant, EnergyIsConservedWithFrictionAndControlOff) {
  const Scenario s = passive_scenario();
  const TwinArm arm(s);
  TwinPlant plant(arm, twin_friction(), s.effects, 1.0 / s.inner_rate_hz);
  plant.reset(TwinVector(0.2, 0.5, -0.8, 0.4), TwinVector(1.0, -0.5, 0.8, 1.5));
  const double e0 = plant.energy();
  double max_kinetic = 0.0, max_drift = 0.0;
  for (int k = 0; k < 10 * 2000; ++k) {
    plant.step(TwinVector::Zero(), TwinVector::Ones());
    max_drift = std::max(max_drift, std::abs(plant.energy() - e0));
    max_kinetic = std::max(max_kinetic, plant.energy() - arm.energy(plant.q(), TwinVector::Zero()));
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
  plant.reset(TwinVector::Zero(), TwinVector(1.0, -1.0, 1.5, -2.0));
  double previous = plant.energy();
  for (int k = 0; k < 4000; ++k) {
    plant.step(TwinVector::Zero(), TwinVector::Ones());
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
    plant.reset(TwinVector::Zero(), TwinVector::Zero());
    // Ramp the torque up over 1 s (quasi-static), then hold it for 1 s.
    const double target = share * friction.stribeck.static_friction[0];
    TwinVector tau = TwinVector::Zero();
    for (int k = 0; k < 4000; ++k) {
      tau[0] = target * std::min(1.0, k / 2000.0);
      plant.step(tau, TwinVector::Ones());
    }
    if (share < 1.0) {
      // Only pre-sliding: quasi-statically dz/dx = 1 − σ0·z/τ_s, so holding 0.8·τ_s takes
      // x = −ln(0.2)·τ_s/σ0 ≈ 1.6·τ_s/σ0 (inertia and drift add a little).
      const double z_max = friction.stribeck.static_friction[0] / friction.bristle_stiffness[0];
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
  const TwinVector q(0.1, 0.4, -0.6, 0.2);
  // The extra gravity torque is J_v(p)ᵀ·(−m·g) at the payload's world point.
  const TwinVector extra = loaded.gravity(q) - bare.gravity(q);
  // Use a pad-free check: finite difference of the payload's potential energy m·g·z(q).
  const double h = 1e-6;
  for (int j = 0; j < kTwinJoints; ++j) {
    TwinVector a = q, b = q;
    a[j] += h;
    b[j] -= h;
    const double dv = (loaded.energy(a, TwinVector::Zero()) - bare.energy(a, TwinVector::Zero()) -
                       loaded.energy(b, TwinVector::Zero()) + bare.energy(b, TwinVector::Zero())) /
                      (2 * h);
    EXPECT_NEAR(extra[j], dv, 1e-6);
  }
  EXPECT_GT(extra.cwiseAbs().maxCoeff(), 0.05);
}

}  // namespace
