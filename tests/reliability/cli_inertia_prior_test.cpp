// The inertia prior of `tpf identify` and `tpf diagnose` (on by default) on the measured Kinova
// Gen3 fitting files, whose plain fit (--no-inertia-prior) has an M(q) that is not positive
// definite: the prior's strength is printed and kept in the file's fit and in diagnose's JSON,
// the model is consistent, diagnose's --identify-out fit is identify's, byte for byte, and its
// written model is physical; the plain fit says what is wrong and how to avoid it; where the
// prior is not needed, or a robot file's own M(q) sets no floor, identify says so.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"
#include "offline/identify/identify.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::test {
namespace {

const std::string kGen3 = std::string(TPF_TEST_DATA_DIR) + "/real/kinova-gen3/";

TEST(CliInertiaPrior, IdentifyAndDiagnoseSayWhatThePriorDidAndAgree) {
  CliSandbox box("inertia_prior");
  const std::string logs = kGen3 + "logs/";
  const std::string fit = " --log " + logs + "RunTrajectory1.csv.gz " + logs +
                          "Trajectory1.csv.gz " + logs + "RecordTrajectory_quadratic.csv.gz" +
                          " --robot " + kGen3 + "gen3.robot.json";

  const CliResult with = box.tpf("identify --quiet" + fit + " --out p.json");
  ASSERT_EQ(with.exit_code, 0) << with.err;
  EXPECT_NE(with.out.find("consistency: ok"), std::string::npos) << with.out;
  EXPECT_NE(with.out.find("inertia prior: M(q)'s smallest eigenvalue without it -2.233 kg·m² "
                          "(judged fit), -2.069 (written fit)"),
            std::string::npos)
      << with.out;
  const nlohmann::json prior =
      nlohmann::json::parse(CliSandbox::slurp(box / "p.json"))["fit"]["inertia_prior"];
  EXPECT_GT(prior["written_strength"].get<double>(), 0.0);
  EXPECT_LT(prior["written_strength"].get<double>(), 1.0);
  EXPECT_NEAR(prior["written_min_mass_eigenvalue_without"].get<double>(), -2.069, 1e-3);

  const CliResult both =
      box.tpf("diagnose --quiet" + fit + " --json d.json --params pd.json --identify-out p2.json");
  ASSERT_EQ(both.exit_code, 0) << both.err;
  EXPECT_EQ(CliSandbox::slurp(box / "p2.json"), CliSandbox::slurp(box / "p.json"));
  EXPECT_NE(both.out.find("inertia prior: M(q)'s smallest eigenvalue without it"),
            std::string::npos)
      << both.out;
  const nlohmann::json diagnosis = nlohmann::json::parse(CliSandbox::slurp(box / "d.json"));
  EXPECT_GT(diagnosis["inertia_prior"]["strength"].get<double>(), 0.0);
  EXPECT_LT(diagnosis["inertia_prior"]["min_mass_eigenvalue_without"].get<double>(), 0.0);
  // Its written model, refitted on every row (the held-out file too), is physical as well.
  const NominalModelX diagnosed = load_nominal_model(box / "pd.json", kGen3 + "gen3.robot.json");
  EXPECT_GT(offline::min_mass_eigenvalue(diagnosed), 0.0);

  // Switched off: the plain fit, its M(q) not positive definite, and the way back.
  const CliResult plain = box.tpf("identify --quiet --no-inertia-prior" + fit + " --out q.json");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(plain.out.find("consistency: PROBLEMS (min eigenvalue of M(q) -2.069 kg·m²)"),
            std::string::npos)
      << plain.out;
  EXPECT_NE(plain.out.find("identify again without --no-inertia-prior"), std::string::npos)
      << plain.out;
  EXPECT_FALSE(
      nlohmann::json::parse(CliSandbox::slurp(box / "q.json"))["fit"].contains("inertia_prior"));

  // On a log that excites every inertia, it says it was not needed.
  ASSERT_EQ(box.tpf("simulate --scenario " + std::string(TPF_TEST_DATA_DIR) +
                    "/scenarios/bench1-excitation.json --seed 3 --duration 20 --out bench.csv")
                .exit_code,
            0);
  const CliResult bench =
      box.tpf("identify --quiet --log bench.csv --robot " + std::string(TPF_TEST_DATA_DIR) +
              "/bench1.robot.json --out b.json");
  ASSERT_EQ(bench.exit_code, 0) << bench.err;
  EXPECT_NE(bench.out.find("inertia prior: not needed"), std::string::npos) << bench.out;

  // A robot file whose own M(q) is singular (a massless pendulum, no rotor inertia) sets no floor:
  // the prior is not applied, and identify says why.
  box.write(
      "massless.urdf",
      R"(<robot name="massless"><link name="stand"/><joint name="joint1" type="revolute">)"
      R"(<parent link="stand"/><child link="pendulum"/><origin xyz="0 0 0.5"/>)"
      R"(<axis xyz="0 1 0"/><limit lower="-2.9" upper="2.9" effort="20" velocity="3"/>)"
      R"(</joint><link name="pendulum"><inertial><mass value="0"/>)"
      R"(<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link></robot>)");
  box.write("massless.robot.json",
            R"({"format": "tpf-robot", "version": 1, "name": "massless", "urdf": "massless.urdf",)"
            R"( "gravity": [0, 0, -9.81], "joints": [{"name": "joint1", "gear_ratio": 100,)"
            R"( "rotor_inertia": 0, "torque_constant": 5, "current_limit": 4000}]})");
  const CliResult massless =
      box.tpf("identify --quiet --log bench.csv --robot massless.robot.json --out m.json");
  ASSERT_EQ(massless.exit_code, 0) << massless.err;
  EXPECT_NE(massless.out.find("inertia prior: not applied: the robot file's own M(q) is not "
                              "positive definite (smallest eigenvalue 0 kg·m²"),
            std::string::npos)
      << massless.out;
  EXPECT_EQ(massless.out.find("inertia prior: not needed"), std::string::npos);
  const nlohmann::json not_applied =
      nlohmann::json::parse(CliSandbox::slurp(box / "m.json"))["fit"]["inertia_prior"];
  EXPECT_FALSE(not_applied["applied"].get<bool>());
}

}  // namespace
}  // namespace tpf::test
