// The compensator's held-out goals on logs the twin did not make (planar_arm_generator: Dahl
// friction with memory, noise, quantisation, random stops), by the evaluate protocol: identify
// on a training log, train one network per joint on it, calibrate on a second log, score Table I
// on a third. Goals: static ≤ −95 %, static-to-kinetic ≤ −75 %, moving no worse than the
// nominal model.
//
// At rest this plant's effort noise (0.02 N·m + a 0.005 N·m quantum) is 5.9 % of the nominal
// static RMSE (0.34 N·m), so −95 % lies below the noise floor: no estimator of the friction can
// reach it. What is checked at rest is what the goal stands for there: the friction's memory
// (the static residual above the floor, rest_memory) removed by ≥ 95 % on each joint.
//
// q is masked (as on the measured arm): with it the network fitted the training motion's poses,
// and joint 2's held-out moving error rose 78 % (0.086 → 0.154 N·m on a 600 s training log).
// Measured: static 0.341 → 0.024 N·m (−93 %, joints 1.3× and 1.05× the floor, memory removed
// 96.0 % and 97.5 %), static-to-kinetic 0.556 → 0.072 (−87 %), moving 0.062 → 0.039 (−37 %).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "offline/compensator_training/train_compensator.hpp"
#include "offline/evaluate/evaluation.hpp"
#include "offline/identify/identify.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "planar_arm_generator.hpp"
#include "tpf/model/load_robot.hpp"
#include "tpf/nn/load_tcn_weights.hpp"

namespace tpf::offline {
namespace {

Log planar_compensator_log(std::uint64_t seed, double seconds) {
  test::PlanarArmPlant plant;
  plant.seed = seed;
  plant.duration_s = seconds;
  plant.rate_hz = 400.0;  // the twin's and the arm loop's rate
  return test::generate_planar_log(plant);
}

const ResidualRow& pooled_row(const Evaluation& ev, Regime regime) {
  for (const ResidualRow& r : ev.table)
    if (r.joint == -1 && r.regime == regime) return r;
  ADD_FAILURE() << "no pooled row for " << regime_name(regime);
  return ev.table.front();
}

Evaluation evaluate_trained_compensator() {
  const Log training = planar_compensator_log(1, 300.0),
            calibration = planar_compensator_log(2, 60.0),
            held_out = planar_compensator_log(3, 120.0);
  const ModelX model = load_robot<double, Eigen::Dynamic>(test::planar_robot_file());
  ReplaySetup setup;
  setup.nominal = identify(training, model).nominal;
  setup.parameters = estimator_parameters_from_noise(
      estimate_sensor_noise(training, setup.nominal.model.torque_constant));

  CompensatorTrainingOptions o;
  o.per_joint = true;
  o.masked_inputs = {kPositionInput};
  o.tcn.max_epochs = 50;  // 100 gave the same figures within 1 % at twice the time
  o.tcn.threads = 2;
  o.tcn.seed = 1;
  const CompensatorTraining trained = train_compensator(
      {replay_estimator(setup, estimator_samples(training, setup.nominal.model, 0))}, o);
  const auto dir = std::filesystem::temp_directory_path() /
                   ("tpf-generator-table-" + std::to_string(::getpid()));
  write_compensator(trained, dir / "planar.tcn.json");
  setup.weights = find_compensator_weights(dir / "planar.tcn.json", 2);

  EvaluationLogs logs;
  logs.calibration = &calibration;
  logs.excitation = {&held_out};
  Evaluation ev = evaluate(setup, logs);
  std::filesystem::remove_all(dir);
  return ev;
}

TEST(GeneratorCompensator, MeetsTheHeldOutGoalsOfTableOne) {
  const Evaluation ev = evaluate_trained_compensator();
  const ResidualRow& rest = pooled_row(ev, Regime::Static);
  const ResidualRow& onset = pooled_row(ev, Regime::StaticToKinetic);
  const ResidualRow& moving = pooled_row(ev, Regime::Moving);
  std::printf("  static %.4f -> %.4f, static-to-kinetic %.4f -> %.4f, moving %.4f -> %.4f N·m\n",
              rest.nominal.rmse, rest.compensated.rmse, onset.nominal.rmse, onset.compensated.rmse,
              moving.nominal.rmse, moving.compensated.rmse);
  EXPECT_LE(onset.compensated.rmse, 0.25 * onset.nominal.rmse);
  EXPECT_LE(moving.compensated.rmse, moving.nominal.rmse);

  ASSERT_EQ(ev.rest_memory.size(), 2u);
  for (const RestMemoryRow& m : ev.rest_memory) {
    std::printf(
        "  joint %d at rest: floor %.4f N·m (%.1f %% of nominal), memory %.4f -> %.4f, "
        "removed %.1f %%, left %.2fx the floor\n",
        m.joint + 1, m.noise_floor, 100.0 * m.noise_floor / m.nominal_rmse, m.nominal_memory,
        m.compensated_memory, 100.0 * m.removed_share, m.compensated_times_floor);
    // The plant's noise: 0.02 N·m and the quantum's 0.005/√12.
    EXPECT_NEAR(m.noise_floor, 0.0201, 0.001) << "joint " << m.joint + 1;
    EXPECT_GT(m.noise_floor, 0.05 * m.nominal_rmse) << "the static goal is above the floor";
    EXPECT_GE(m.removed_share, 0.95) << "joint " << m.joint + 1;
  }
}

}  // namespace
}  // namespace tpf::offline
