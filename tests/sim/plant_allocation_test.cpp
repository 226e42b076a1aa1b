// The twin's plant allocates nothing per step after the first (its workspace is sized once): on
// the 4-joint arm with each friction model and the position-dependent effects, on the same arm
// with a coupled wrist (motor 4 turns with q₄ + q₃: the coupled friction step), and on the 9-joint
// arm of tests/sim/arm9; nor does the simulation loop between two logged rows (excitation with
// undeclared effects and a current delay, static contacts; uncoupled and coupled). Under
// AddressSanitizer, heap traffic per step was a third of the simulation's time.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <fstream>
#include <span>
#include <string>

#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "offline/sim/twin_arm.hpp"
#include "offline/sim/twin_plant.hpp"
#include "support/allocation_counter.hpp"
#include "support/temp_dir.hpp"

namespace {

using namespace tpf::offline;

/// Heap allocations of `steps` plant steps after a first one, from the scenario's initial pose.
std::size_t allocations_after_first_step(const Scenario& s, int steps) {
  const TwinArm arm(s);
  const int n = arm.joints();
  TwinFriction friction{std::vector<JointFriction>(static_cast<std::size_t>(n))};
  if (s.effects.friction != EffectsConfig::Friction::kNone)
    friction = load_twin_friction(s.friction_file, n);
  TwinPlant plant(arm, friction, s.effects, 1.0 / s.inner_rate_hz);
  plant.reset(s.initial_q, TwinVector::Constant(n, 0.3));
  const TwinVector tau = TwinVector::Constant(n, 0.5), viscous_scale = TwinVector::Ones(n);
  plant.step(tau, viscous_scale);
  const std::size_t before = tpf::test::heap_allocation_count();
  for (int k = 0; k < steps; ++k)
    plant.step(tau, viscous_scale);
  const std::size_t count = tpf::test::heap_allocation_count() - before;
  EXPECT_TRUE(plant.q().allFinite());
  return count;
}

// data/arm4.robot.json with a differential wrist: motor 4 coupled_to joint3 (c = 1), written to
// `dir` (its URDF, pads and friction from data/).
std::string coupled_arm4(const tpf::test::TempDir& dir) {
  const std::string data = TPF_TEST_DATA_DIR;
  const std::string path = (dir / "arm4_coupled.robot.json").string();
  std::ofstream out(path);
  out << R"({"format": "tpf-robot", "version": 1, "name": "arm4_coupled",)"
      << R"( "urdf": ")" << data << R"(/arm4.urdf", "pads": ")" << data << R"(/arm4.pads.json",)"
      << R"( "friction": ")" << data << R"(/arm4.friction.json", "joints": [)";
  for (int j = 1; j <= 4; ++j) {
    const bool big = j <= 2;  // PH54-200 on joints 1-2, PH54-100 on 3-4
    out << (j > 1 ? ", " : "") << R"({"name": "joint)" << j
        << R"(", "gear_ratio": 501.923, "rotor_inertia": )" << (big ? "3.33e-6" : "0.89e-6")
        << R"(, "torque_constant": )" << (big ? "4.81" : "4.60") << R"(, "current_limit": )"
        << (big ? "22740" : "15900") << (j == 4 ? R"(, "coupled_to": {"joint3": 1.0})" : "") << "}";
  }
  out << "]}";
  return path;
}

Scenario with_position_effects(Scenario s) {
  const int n = static_cast<int>(s.initial_q.size());
  s.effects.ripple.enabled = true;
  s.effects.ripple.amplitude = TwinVector::Constant(n, 0.05);
  s.effects.ripple.cycles_per_rev = TwinVector::Constant(n, 12.0);
  s.effects.ripple.phase = TwinVector::Zero(n);
  s.effects.spring.enabled = true;
  s.effects.spring.stiffness = TwinVector::Constant(n, 0.2);
  s.effects.spring.neutral = TwinVector::Zero(n);
  return s;
}

TEST(TwinPlantAllocation, StepsAfterTheFirstAllocateNothing) {
  if (!tpf::test::mallocs_are_counted()) GTEST_SKIP() << "malloc is not counted on this platform";
  const Scenario base = with_position_effects(
      load_scenario(TPF_TEST_DATA_DIR "/scenarios/excitation-undeclared.json"));
  for (const auto friction : {EffectsConfig::Friction::kLuGre, EffectsConfig::Friction::kStribeck,
                              EffectsConfig::Friction::kNone}) {
    for (const bool load_dependent : {true, false}) {
      Scenario s = base;
      s.effects.friction = friction;
      s.effects.load_dependent_friction = load_dependent;
      EXPECT_EQ(allocations_after_first_step(s, 200), 0u)
          << "friction model " << static_cast<int>(friction) << ", load-dependent "
          << load_dependent;
    }
  }
}

TEST(TwinPlantAllocation, CoupledStepsAfterTheFirstAllocateNothing) {
  if (!tpf::test::mallocs_are_counted()) GTEST_SKIP() << "malloc is not counted on this platform";
  const tpf::test::TempDir dir("coupled_allocation");
  const Scenario base = with_position_effects(
      load_scenario(TPF_TEST_DATA_DIR "/scenarios/excitation-undeclared.json", coupled_arm4(dir)));
  ASSERT_TRUE(TwinArm(base).coupled());
  for (const auto friction :
       {EffectsConfig::Friction::kLuGre, EffectsConfig::Friction::kStribeck}) {
    Scenario s = base;
    s.effects.friction = friction;
    EXPECT_EQ(allocations_after_first_step(s, 200), 0u)
        << "friction model " << static_cast<int>(friction);
  }
}

TEST(TwinPlantAllocation, NineJointStepsAfterTheFirstAllocateNothing) {
  if (!tpf::test::mallocs_are_counted()) GTEST_SKIP() << "malloc is not counted on this platform";
  const Scenario s = load_scenario(std::string(TPF_SIM_TEST_DIR "/arm9/arm9-excitation.json"));
  ASSERT_EQ(s.initial_q.size(), 9);
  EXPECT_EQ(allocations_after_first_step(s, 200), 0u);
}

/// Heap allocations of the simulation loop between logged rows, summed over the rows after the
/// first two (10 inner steps each at the scenario's 4 kHz and 400 Hz).
std::size_t allocations_between_rows(const Scenario& s, double duration_s) {
  std::size_t rows = 0, previous = 0, between = 0;
  simulate(s, 11, duration_s, [&](std::span<const double>) {
    const std::size_t now = tpf::test::heap_allocation_count();
    if (rows >= 2) between += now - previous;
    ++rows;
    previous = tpf::test::heap_allocation_count();
  });
  EXPECT_GT(rows, 100u);
  return between;
}

TEST(TwinPlantAllocation, SimulationStepsAllocateNothing) {
  if (!tpf::test::mallocs_are_counted()) GTEST_SKIP() << "malloc is not counted on this platform";
  Scenario undeclared = load_scenario(TPF_TEST_DATA_DIR "/scenarios/excitation-undeclared.json");
  undeclared.effects.delay.enabled = true;
  undeclared.effects.delay.delay_s = 0.002;
  EXPECT_EQ(allocations_between_rows(undeclared, 3.0), 0u) << "excitation, undeclared effects";
  const Scenario contacts = load_scenario(TPF_TEST_DATA_DIR "/scenarios/static-contacts.json");
  EXPECT_EQ(allocations_between_rows(contacts, 3.0), 0u) << "static contacts";

  const tpf::test::TempDir dir("coupled_simulation_allocation");
  const std::string coupled = coupled_arm4(dir);
  Scenario coupled_undeclared =
      load_scenario(TPF_TEST_DATA_DIR "/scenarios/excitation-undeclared.json", coupled);
  coupled_undeclared.effects.delay.enabled = true;
  coupled_undeclared.effects.delay.delay_s = 0.002;
  EXPECT_EQ(allocations_between_rows(coupled_undeclared, 3.0), 0u) << "coupled wrist, excitation";
  EXPECT_EQ(allocations_between_rows(
                load_scenario(TPF_TEST_DATA_DIR "/scenarios/static-contacts.json", coupled), 3.0),
            0u)
      << "coupled wrist, static contacts";
}

}  // namespace
