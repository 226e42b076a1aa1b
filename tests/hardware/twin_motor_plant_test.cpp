// The digital twin behind the emulated motors and pads (TwinMotorPlant), stepped directly:
// the PH54 drive cascade holds a pose, current mode follows its goal, torque off draws no
// current, a scripted push reaches the pads with the twin's gain and is recorded as ground truth.
#include "twin/twin_motor_plant.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

#include "offline/sim/twin_arm.hpp"

namespace tpf::dxl::emu {
namespace {

offline::Scenario static_contacts() {
  return offline::load_scenario(std::string(TPF_TEST_DATA_DIR) + "/scenarios/static-contacts.json");
}

std::array<MotorGoal, 4> hold(const offline::TwinVector& q) {
  std::array<MotorGoal, 4> goals{};
  for (int j = 0; j < 4; ++j) {
    goals[j].mode = ph54::OperatingMode::position;
    goals[j].torque_enabled = true;
    goals[j].position_rad = q[j];
  }
  return goals;
}

/// Steps the plant for `seconds` in 1 ms pieces (as the emulator does).
void run(TwinMotorPlant& plant, double seconds, std::span<const MotorGoal> goals) {
  for (int n = 0; n < static_cast<int>(seconds * 1000.0 + 0.5); ++n)
    plant.step(1e-3, goals);
}

TEST(TwinMotorPlant, DrivesHoldThePoseAgainstGravityAndAPush) {
  const offline::Scenario scenario = static_contacts();
  TwinMotorPlant plant(scenario, {3, 20000});
  offline::ContactScript push;
  offline::ContactEvent e;
  e.pad = 4;  // forearm_top
  e.t_on = 1.0;
  e.t_full = 1.25;
  e.t_release = 2.5;
  e.t_off = 2.75;
  e.normal_n = 10.0;
  e.area_cm2 = 6.0;  // the reference area: gain exactly 1.5 kPa/N
  push.add(e);
  plant.set_contacts(push);
  const auto goals = hold(scenario.initial_q);
  run(plant, 2.0, goals);

  EXPECT_NEAR(plant.time(), 2.0, 1e-9);
  const offline::TwinArm arm(scenario);
  for (int j = 0; j < 4; ++j) {
    // Held within a few mrad of the goal (the position loop's integrator removes the sag).
    EXPECT_NEAR(plant.state(j).position_rad, scenario.initial_q[j], 5e-3) << j;
    EXPECT_NEAR(plant.state(j).velocity_rad_s, 0.0, 1e-2) << j;
  }
  // The pushed pad reads 1.5 kPa/N · 10 N (first-order lag 15 ms, long settled), ± noise/drift.
  std::array<float, 16> kpa{};
  ASSERT_EQ(plant.pad_pressures(kpa), arm.pad_count());
  EXPECT_NEAR(kpa[4], 15.0, 0.3);
  for (int k = 0; k < arm.pad_count(); ++k) {
    if (k == 4) continue;
    EXPECT_LT(kpa[static_cast<std::size_t>(k)], 0.3f) << k;
  }
  // Ground truth: the push's joint torque J_vᵀF while held, none before.
  const TwinTruth& before = plant.truth()[static_cast<std::size_t>(0.9 * 2000)];
  const TwinTruth& during = plant.truth()[static_cast<std::size_t>(1.9 * 2000)];
  EXPECT_EQ(before.pad, -1);
  EXPECT_EQ(before.tau_ext.norm(), 0.0);
  EXPECT_EQ(during.pad, 4);
  EXPECT_NEAR(during.normal_force_n, 10.0, 1e-9);
  EXPECT_GT(during.tau_ext.norm(), 0.5);
}

TEST(TwinMotorPlant, CurrentModeFollowsTheGoalAndTorqueOffDrawsNothing) {
  TwinMotorPlant plant(static_contacts(), {5, 0});
  std::array<MotorGoal, 4> goals{};
  for (auto& g : goals) {
    g.mode = ph54::OperatingMode::current;
    g.torque_enabled = true;
    g.current_A = 0.4;
  }
  goals[3].torque_enabled = false;
  run(plant, 0.02, goals);  // 67 current-loop time constants (0.3 ms)
  for (int j = 0; j < 3; ++j)
    EXPECT_NEAR(plant.state(j).current_A, 0.4, 0.03) << j;  // ± 5σ of the 6 mA noise
  EXPECT_NEAR(plant.state(3).current_A, 0.0, 0.03);
}

}  // namespace
}  // namespace tpf::dxl::emu
