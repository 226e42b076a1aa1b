// The whole loop — simulate → identify → diagnose → train → calibrate → evaluate — on arms other
// than the demo's (SIMULATED, short logs): the 1-joint test bench and the 7-joint Kinova Gen3
// without skin (the 4-joint arm with its pads is DemoPipeline's). Each stage's result is checked
// against what the twin planted: the identified model explains the held-out effort far better
// than no model, the calibrated estimator loads into the run-time type, the pad rows say no skin.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "offline/calibrate/estimator_calibration.hpp"
#include "offline/compensator_training/train_compensator.hpp"
#include "offline/diagnose/diagnose.hpp"
#include "offline/evaluate/evaluation.hpp"
#include "offline/identify/identify.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::offline {
namespace {

std::string data(const std::string& name) {
  return std::string(TPF_TEST_DATA_DIR) + "/" + name;
}

/// RMSE of a column set over the finite rows.
double effort_rms(const Log& log, int joint) {
  const auto e = log.col(indexed_name(log.effort_prefix(), joint + 1));
  double sum = 0;
  int n = 0;
  for (Eigen::Index k = 0; k < e.size(); ++k)
    if (std::isfinite(e[k])) sum += e[k] * e[k], ++n;
  return std::sqrt(sum / std::max(n, 1));
}

/// `fit_bar`: the identified model's moving residual must be below this share of the held-out
/// effort on every joint (0: not checked).
template <int N>
void run_loop(const std::string& robot, const std::string& scenario, double seconds,
              double fit_bar) {
  const Scenario s = load_scenario(data("scenarios/" + scenario));
  Log training = simulate_to_log(s, 1, seconds);
  Log calibration = simulate_to_log(s, 2, seconds / 2);
  Log held_out = simulate_to_log(s, 3, seconds / 2);
  ASSERT_EQ(training.joint_count(), N);
  ASSERT_EQ(training.pad_count(), 0) << "no skin: no pad columns";

  // identify, then diagnose (its model is the nominal model of the loop)
  const Model<double, N> model = load_robot<double, N>(data(robot));
  // The twin's drive holds the rigid body the robot file declares; where the log is too short
  // to excite every inertia, the inertia prior (on by default) keeps M(q) positive definite.
  const Model<double, Eigen::Dynamic> any_model = joint_count_cast<Eigen::Dynamic>(model);
  const Identification identified = identify(training, any_model, {});
  EXPECT_TRUE(identified.consistency.consistent())
      << robot << ": "
      << (identified.consistency.problems.empty() ? "" : identified.consistency.problems[0]);
  const Diagnosis diagnosis = diagnose(training, any_model, {});
  ReplaySetup setup;
  setup.nominal = diagnosis.nominal;

  // train a small compensator on the training log
  setup.parameters = estimator_parameters_from_noise(
      estimate_sensor_noise(training, setup.nominal.model.torque_constant));
  const std::vector<EstimatorTrace> traces{
      replay_estimator(setup, estimator_samples(training, setup.nominal.model, 0))};
  CompensatorTrainingOptions training_options;
  training_options.per_joint = true;
  training_options.tcn.max_epochs = 2;
  const CompensatorTraining trained = train_compensator(traces, training_options);
  ASSERT_EQ(trained.results.size(), static_cast<std::size_t>(N));
  const auto dir = std::filesystem::temp_directory_path() /
                   ("tpf_any_arm_loop_" + std::to_string(N) + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  write_compensator(trained, dir / "tcn.json");
  setup.weights = find_compensator_weights(dir / "tcn.json", N);

  // calibrate, then evaluate on the held-out log
  setup.parameters = calibrate_estimator(setup, calibration);
  EvaluationLogs logs;
  logs.calibration = &calibration;
  logs.excitation = {&held_out};
  const Evaluation ev = evaluate(setup, logs);
  EXPECT_EQ(ev.joints, N);
  EXPECT_FALSE(ev.has_skin);
  EXPECT_EQ(ev.table.size(), static_cast<std::size_t>(3 * (N + 1)));  // (N + all) × 3 regimes
  // The nominal model explains the held-out effort: on every joint its moving residual is well
  // below the effort itself (gravity and friction dominate the drive's current).
  for (const ResidualRow& row : ev.table) {
    if (row.joint < 0 || row.regime != Regime::Moving || row.nominal.count == 0) continue;
    EXPECT_TRUE(std::isfinite(row.nominal.rmse) && std::isfinite(row.compensated.rmse));
    if (fit_bar > 0) {
      EXPECT_LT(row.nominal.rmse, fit_bar * effort_rms(held_out, row.joint))
          << robot << " joint " << row.joint + 1;
    }
  }
  EXPECT_NE(evaluation_json(ev).find("\"tactile_n\": \"no skin\""), std::string::npos);

  // What calibrate wrote loads into the run-time estimator of this arm (no skin).
  save_nominal_model(dir / "model.params.json", setup.nominal, "loop test");
  save_estimator_parameters(dir / "model.estimator.json", setup.parameters, "loop test");
  EXPECT_NO_THROW((load_estimator<N, 0, PerJointTcn<BFloat16Weights, 16>>(
      {(dir / "model.params.json").string(), data(robot), "",
       (dir / "model.estimator.json").string(), (dir / "tcn.json").string()})));
  std::filesystem::remove_all(dir);
}

TEST(AnyArmLoop, OneJointBench) {
  run_loop<1>("bench1.robot.json", "bench1-excitation.json", 40, 0.5);
}

TEST(AnyArmLoop, SevenJointKinovaWithoutSkin) {
  // Short logs of the twin's excitation do not excite every inertia of the Kinova's 51 base
  // parameters (the plain fit's M(q) is not positive definite; the inertia prior makes it so):
  // the loop runs on 20 s, the fit's residual is not judged here (docs/identification.md).
  run_loop<7>("real/kinova-gen3/gen3.robot.json", "kinova-gen3-excitation.json", 20, 0.0);
}

}  // namespace
}  // namespace tpf::offline
