// The built `tpf` on an arm of 9 joints (tests/sim/arm9, six pads): simulate, then calibrate,
// evaluate and validate with the arm's true nominal model — every estimator-side command takes an
// arm of any joint count — and the log/robot joint-count mismatch is refused naming both files.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "cli_runner.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

/// The 9-joint test arm's files: tests/sim/arm9/<name>.
std::string arm9(const std::string& name) {
  return kShippedData + "/../tests/sim/arm9/" + name;
}

TEST(CliNineJointTools, CalibrateEvaluateAndValidateANineJointArm) {
  CliSandbox box("nine_joint_tools");
  // The true model of the twin's arm: the robot file's rigid body, the friction file's curve.
  save_nominal_model(box / "arm9.params.json",
                     nominal_from_model(load_robot<double, Eigen::Dynamic>(arm9("arm9.robot.json")),
                                        load_stribeck_parameters(arm9("arm9.friction.json"), 9)),
                     "true model of tests/sim/arm9");
  box.write("contacts.json",
            "{\"kind\": \"static-contacts\", \"name\": \"arm9 pushes\", "
            "\"robot\": \"" +
                arm9("arm9.robot.json") + "\"}");
  const std::string excitation = " --scenario " + arm9("arm9-excitation.json");
  for (const std::string& run :
       {"simulate" + excitation + " --seed 31 --duration 30 --out calibration.csv",
        "simulate" + excitation + " --seed 32 --duration 15 --out held-out.csv",
        std::string(
            "simulate --scenario contacts.json --seed 33 --duration 30 --out contacts.csv")}) {
    const CliResult r = box.tpf(run);
    ASSERT_EQ(r.exit_code, 0) << run << "\n" << r.err;
  }
  const std::string model = " --params arm9.params.json --robot " + arm9("arm9.robot.json");

  const CliResult calibrate =
      box.tpf("calibrate --log calibration.csv" + model + " --out arm9.estimator.json");
  ASSERT_EQ(calibrate.exit_code, 0) << calibrate.err;
  EXPECT_NE(calibrate.out.find("9 joints, 6 pads"), std::string::npos) << calibrate.out;
  const auto parameters = load_estimator_parameters(box / "arm9.estimator.json", 9);
  EXPECT_EQ(parameters.joint_count(), 9);
  EXPECT_GT(parameters.static_dead_band.minCoeff(), 0.0);

  const CliResult evaluate =
      box.tpf("evaluate --quiet" + model +
              " --calibration calibration.csv --excitation held-out.csv --contacts contacts.csv "
              "--out report");
  ASSERT_EQ(evaluate.exit_code, 0) << evaluate.err;
  const auto json = nlohmann::json::parse(CliSandbox::slurp(box / "report/evaluation.json"));
  EXPECT_EQ(json["sigma"]["nominal"].size(), 9u);
  EXPECT_EQ(json["dead_bands"]["fusion_static"].size(), 9u);
  EXPECT_EQ(json["residual_table"].size(), 30u);  // (9 joints + all) × 3 regimes
  const auto& fusion = json["detection"]["fusion"];
  EXPECT_GE(fusion["events"].get<int>(), 3);
  EXPECT_EQ(fusion["detected"], fusion["events"]);

  const CliResult validate = box.tpf("validate" + model + " --log held-out.csv");
  ASSERT_EQ(validate.exit_code, 0) << validate.err;
  EXPECT_NE(validate.out.find("joint 9"), std::string::npos) << validate.out;

  // A log of 9 joints with the robot file of another arm: refused, naming both.
  const CliResult mismatch = box.tpf("validate --params arm9.params.json --robot " + kShippedData +
                                     "/arm4.robot.json --log held-out.csv");
  EXPECT_EQ(mismatch.exit_code, 1);
  EXPECT_NE(mismatch.err.find("the log has 9 joints (q1 … q9), the robot file"), std::string::npos)
      << mismatch.err;
  EXPECT_NE(mismatch.err.find("arm4.robot.json has 4"), std::string::npos) << mismatch.err;
}

}  // namespace
}  // namespace tpf::test
