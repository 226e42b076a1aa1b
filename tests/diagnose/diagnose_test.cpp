// Diagnosis on twin logs with undeclared effects: named when present, nothing claimed when clean.
// The twin's parameters are never handed to the diagnosis: it sees the log and the robot file.
#include "offline/diagnose/diagnose.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "offline/diagnose/diagnosis_report.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/arm_fixture.hpp"

namespace tpf::test {
namespace {

using offline::Diagnosis;

offline::Scenario clean_scenario() {
  auto scenario = offline::load_scenario(data_path("scenarios/excitation.json"));
  scenario.effects.load_dependent_friction = false;
  return scenario;
}

Diagnosis run(const offline::Scenario& scenario, std::uint64_t seed) {
  const offline::Log log = offline::simulate_to_log(scenario, seed, 120.0);
  auto d = offline::diagnose(log, joint_count_cast<Eigen::Dynamic>(arm()));
  for (const auto& t : d.trials)
    if (t.round == 1 || t.selected)
      std::printf("  round %d %-60s %7.2f %% BIC %9.0f %s\n", t.round, t.title.c_str(),
                  100 * t.improvement, t.bic_change, t.selected ? "SELECTED" : "");
  for (const auto& f : d.findings)
    std::printf("  %s\n", f.c_str());
  for (int j = 0; j < kJoints; ++j)
    std::printf("  joint %d static %.1f -> %.1f, moving %.1f -> %.1f, noise %.1f\n", j + 1,
                d.before[j][0].rmse(), d.after[j][0].rmse(), d.before[j][2].rmse(),
                d.after[j][2].rmse(), d.noise_floor[j]);
  return d;
}

std::vector<std::string> selected_keys(const Diagnosis& d) {
  std::vector<std::string> keys;
  for (int g : d.selected)
    keys.push_back(d.groups[g].key);
  return keys;
}

TEST(Diagnose, CleanLogClaimsNothing) {
  const auto d = run(clean_scenario(), 21);
  EXPECT_TRUE(d.selected.empty());
  // One file: held out by time, and the JSON says so.
  EXPECT_EQ(d.heldout_method, "by time blocks: 1 in 4 of interleaved 5 s blocks");
  EXPECT_NE(offline::diagnosis_json(d).find(
                R"("heldout_method": "by time blocks: 1 in 4 of interleaved 5 s blocks")"),
            std::string::npos);
  EXPECT_FALSE(d.cad_payload.claimed) << d.cad_payload.mass << " kg";
}

TEST(Diagnose, FindsAPayloadAgainstTheRobotFilesInertias) {
  // 0.6 kg at (0.08, 0, 0) m on the last link, not in the robot file. The identified rigid body
  // absorbs it (no missing effect), but held against the robot file's inertias it shows.
  auto scenario = clean_scenario();
  scenario.effects.payload.enabled = true;
  scenario.effects.payload.mass = 0.6;
  scenario.effects.payload.position = Vector3<double>(0.08, 0.0, 0.0);
  const auto d = run(scenario, 33);
  EXPECT_TRUE(d.selected.empty());
  ASSERT_TRUE(d.cad_payload.claimed);
  EXPECT_NEAR(d.cad_payload.mass, 0.6, 0.06);
  EXPECT_NEAR(d.cad_payload.centre.x(), 0.08, 0.015);
  EXPECT_NEAR(d.cad_payload.centre.y(), 0.0, 0.015);
  EXPECT_NEAR(d.cad_payload.centre.z(), 0.0, 0.015);
}

TEST(Diagnose, NamesLoadDependentFriction) {
  auto scenario = clean_scenario();
  scenario.effects.load_dependent_friction = true;
  const auto d = run(scenario, 22);
  const auto keys = selected_keys(d);
  ASSERT_FALSE(keys.empty());
  for (const auto& k : keys)
    EXPECT_EQ(k, "load_friction");
  // The effect acts while sliding: the held-out moving RMSE of the most loaded joint (2) drops.
  EXPECT_LT(d.after[1][2].rmse(), 0.85 * d.before[1][2].rmse());
  // At rest the declared model holds sgn(last motion)·F and the load candidate adds
  // sgn(last motion)·α|G| (fitted on static samples). The static residual is dominated by the
  // pre-sliding memory (≈140 mA on joint 2 with or without load friction in the twin, against
  // ≈25 mA of load-dependent variation), so it may not grow but cannot halve
  // (docs/diagnosis.md).
  EXPECT_LE(d.after[1][0].rmse(), 1.01 * d.before[1][0].rmse());
}

TEST(Diagnose, NamesTemperatureDependentFriction) {
  // The arm starts warm (45 °C) and cools towards 25 °C with a 60 s time constant; the viscous
  // friction rises by 1.2 %/K as it cools. The diagnosis sees temp<j>, never the coefficients.
  auto scenario = clean_scenario();
  scenario.effects.thermal.enabled = true;
  scenario.effects.thermal.initial_c = 45.0;
  scenario.effects.thermal.ambient_c = 25.0;
  scenario.effects.thermal.time_constant_s = 60.0;
  scenario.effects.thermal.viscous_per_k = -0.012;
  const auto d = run(scenario, 31);
  const auto keys = selected_keys(d);
  ASSERT_FALSE(keys.empty());
  for (const auto& k : keys)
    EXPECT_EQ(k, "thermal");
  // Friction falls as the joint warms: the fitted β·(T − T_ref)·q̇ coefficient is negative,
  // reported (the run time has no temperature input, so it is not written). If it is named for
  // every joint at once, its coefficient is the twin's relative change of the viscous friction
  // per kelvin.
  for (const auto& c : d.claims) {
    EXPECT_LT(c.coefficients[0], 0.0);
    EXPECT_FALSE(c.written);
    if (d.groups[c.groups[0]].joint == -1) {
      EXPECT_NEAR(c.coefficients[0], -0.012, 0.004);
    }
  }
  // The every-joint form (one relative coefficient, b_j·(T_j − T_ref)·q̇_j) is tried beside the
  // per-joint ones and the data favour it (held-out gain over every joint, BIC down), though its
  // gain spread over four joints stays under the claim threshold on this log (5.8 %).
  bool tried = false;
  for (const auto& t : d.trials)
    if (t.key == "thermal" && t.joint == -1 && t.round == 1) {
      tried = true;
      EXPECT_GT(t.improvement, 0.02);
      EXPECT_LT(t.bic_change, 0.0);
    }
  EXPECT_TRUE(tried);
}

TEST(Diagnose, NamesRippleAndSpring) {
  auto scenario = clean_scenario();
  scenario.effects.ripple.enabled = true;
  scenario.effects.ripple.amplitude = Vec(0.0, 0.35, 0.0, 0.0);
  scenario.effects.ripple.cycles_per_rev = Vec(12, 12, 10, 10);
  scenario.effects.spring.enabled = true;
  scenario.effects.spring.stiffness = Vec(0.0, 0.0, 2.0, 0.0);
  scenario.effects.spring.neutral = Vec(0.0, 0.0, 0.3, 0.0);
  const auto d = run(scenario, 23);
  const auto keys = selected_keys(d);
  EXPECT_NE(std::find(keys.begin(), keys.end(), "ripple"), keys.end());
  EXPECT_NE(std::find(keys.begin(), keys.end(), "spring"), keys.end());
}

}  // namespace
}  // namespace tpf::test
