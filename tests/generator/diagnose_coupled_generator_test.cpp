// Diagnosis of a coupled wrist on the independent generator (planar_arm_generator): motor 2 turns
// with q₂ + 0.5·q₁, three files of 40 s. With the coupled robot file (planar2_coupled.robot.json)
// diagnose fits the coupled model as identify does (motor 2's friction within 5 %) and claims
// nothing; with the uncoupled one (planar2.robot.json) it names the coupled motor of joints 1–2,
// its ratio within 5 %, passing the transfer test, and nothing else (no motion coupling, no
// load-friction stand-in).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "offline/diagnose/diagnose.hpp"
#include "offline/log/log_writer.hpp"
#include "offline/log/read_logs.hpp"
#include "planar_arm_generator.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

constexpr double kPlantedCoupling = 0.5;

PlanarArmPlant coupled_file_plant(std::uint64_t seed = 11) {
  PlanarArmPlant plant;
  plant.seed = seed;
  plant.duration_s = 40.0;
  plant.motor2_coupling = kPlantedCoupling;
  return plant;
}

// Three files of 40 s, seeds 11–13, read as one log: the last held out, and each of the others
// held out in turn for the transfer test.
const offline::Log& coupled_log() {
  static const offline::Log log = [] {
    std::vector<std::filesystem::path> paths;
    for (std::uint64_t f = 0; f < 3; ++f) {
      paths.push_back(
          std::filesystem::temp_directory_path() /
          ("tpf_coupled_" + std::to_string(f + 1) + "_" + std::to_string(::getpid()) + ".csv"));
      offline::write_log(paths.back(), generate_planar_log(coupled_file_plant(11 + f)));
    }
    offline::Log read = offline::read_logs(paths);
    for (const auto& p : paths)
      std::filesystem::remove(p);
    return read;
  }();
  return log;
}

void print(const offline::Diagnosis& d, const char* label) {
  std::printf("  [%s] %zu claims\n", label, d.claims.size());
  for (const auto& t : d.trials)
    if (t.improvement > 0.03 || t.selected)
      std::printf("    round %d %-70s %6.1f %% BIC %8.0f %5.1f SE share %.3f transfer %.1f %%%s\n",
                  t.round, t.title.c_str(), 100 * t.improvement, t.bic_change, t.wald,
                  t.distinct_share, 100 * t.transfer_improvement, t.selected ? " SELECTED" : "");
  for (const auto& f : d.findings)
    std::printf("    %s\n", f.c_str());
}

// Held-out moving RMSE of joint j of the model as written [N·m].
double written_moving(const std::vector<offline::RegimeStats>& table, int j) {
  return table[j][offline::Regime::Moving].rmse;
}

TEST(DiagnoseCoupled, TheCoupledRobotFileLeavesNothingToClaim) {
  const auto model = load_robot<double, Eigen::Dynamic>(planar_coupled_robot_file());
  const offline::Diagnosis d = offline::diagnose(coupled_log(), model);
  print(d, "coupled robot file");
  EXPECT_TRUE(d.claims.empty());
  EXPECT_FALSE(d.cad_payload.claimed);
  EXPECT_TRUE(d.coupled_motors.empty());  // no pair of uncoupled motors to try
  // The coupled model as identify fits it: motor 2's friction on q̇₂ + 0.5·q̇₁.
  EXPECT_TRUE(d.nominal.model.coupled);
  const PlanarArmPlant plant = coupled_file_plant();
  std::printf("  motor 2: τ_c %.4f b %.4f; held-out moving RMSE %.4f %.4f N·m\n",
              d.nominal.friction.coulomb[1], d.nominal.friction.viscous[1],
              written_moving(d.written_after, 0), written_moving(d.written_after, 1));
  EXPECT_NEAR(d.nominal.friction.coulomb[1], plant.coulomb_positive[1],
              0.05 * plant.coulomb_positive[1]);
  EXPECT_NEAR(d.nominal.friction.viscous[1], plant.viscous[1], 0.05 * plant.viscous[1]);
}

TEST(DiagnoseCoupled, NamesTheUndeclaredCoupledMotorAndItsRatio) {
  const auto model = load_robot<double, Eigen::Dynamic>(planar_robot_file());
  const offline::Diagnosis d = offline::diagnose(coupled_log(), model);
  print(d, "uncoupled robot file");
  ASSERT_EQ(d.coupled_motors.size(), 1u);
  const offline::CoupledMotorCandidate& m = d.coupled_motors[0];
  std::printf("  fitted: motor %d rotates with q%d + %.4f·q%d\n", m.own() + 1, m.own() + 1,
              m.ratio(), m.other() + 1);
  EXPECT_EQ(m.own(), 1);
  EXPECT_NEAR(m.ratio(), kPlantedCoupling, 0.05 * kPlantedCoupling);
  ASSERT_EQ(d.claims.size(), 1u);
  const offline::Claim& c = d.claims[0];
  EXPECT_FALSE(c.ambiguous());
  EXPECT_FALSE(c.written);
  const offline::FeatureGroup& g = d.groups[c.groups[0]];
  EXPECT_EQ(g.key, "coupled_motor");
  EXPECT_EQ(g.joints, (std::vector<int>{0, 1}));
  EXPECT_GE(c.improvements[0], 0.5);
  // It passed the transfer test: each other file held out in turn, it removes ≥ 10 % there too.
  // and it lowers each joint's alone: a motor on q₂ + 0.5·q₁ acts on both.
  bool transferred = false, each_joint = false;
  for (const offline::CandidateTrial& t : d.trials)
    if (t.selected) {
      std::printf("  transfer %.1f %%, weakest joint %.1f %%\n", 100 * t.transfer_improvement,
                  100 * t.weakest_joint_improvement);
      transferred = t.key == "coupled_motor" && t.transfer_improvement >= 0.10;
      each_joint = t.weakest_joint_improvement >= 0.10;
    }
  EXPECT_TRUE(transferred);
  EXPECT_TRUE(each_joint);
  // Its Coulomb and viscous coefficients: motor 2's planted friction.
  const PlanarArmPlant plant = coupled_file_plant();
  std::printf("  claim: removes %.1f %%, τ_c %.4f ± %.4f, b %.4f ± %.4f\n", 100 * c.improvements[0],
              c.coefficients[0], c.standard_errors[0], c.coefficients[1], c.standard_errors[1]);
  EXPECT_NEAR(c.coefficients[0], plant.coulomb_positive[1], 0.15 * plant.coulomb_positive[1]);
  EXPECT_FALSE(d.cad_payload.claimed);
}

}  // namespace
}  // namespace tpf::test
