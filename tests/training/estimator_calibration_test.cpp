// tpf calibrate's computation (calibrate_estimator) on a simulated contact-free twin log: it is
// exactly the three calibration steps of tpf evaluate, the compensator it is given is the one
// calibrated (fused σ below nominal σ), and its result survives the estimator parameter file.
#include "offline/calibrate/estimator_calibration.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <limits>

#include "offline/calibrate/torque_alarm.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/constants.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"

namespace tpf::offline {
namespace {

using test::kArm4Joints;
using test::kArm4Pads;
using ArmParameters = ReplayParameters;

std::string data(const std::string& name) {
  return std::string(TPF_TEST_DATA_DIR) + "/" + name;
}

TEST(ArmCalibration, RunsEvaluatesStepsWithTheCompensator) {
  // 20 s of the twin's excitation (simulated): rests and moves on every joint, no contact.
  Log log = simulate_to_log(load_scenario(data("scenarios/excitation.json")), 11, 20.0);
  log.source = "excitation seed 11 (simulated)";
  ReplaySetup setup;
  setup.nominal = load_nominal_model(data("arm4.params.json"), data("arm4.robot.json"));
  setup.pads = load_pads(data("arm4.pads.json"), setup.nominal.model);
  setup.weights = find_compensator_weights(data("weights/arm4.tcn.json"), kArm4Joints);
  const ArmParameters p = calibrate_estimator(setup, log, 1.5);

  // The steps, one by one, as tpf evaluate runs them.
  ReplaySetup steps = setup;
  steps.parameters = estimator_parameters_from_noise(
      estimate_sensor_noise(log, steps.nominal.model.torque_constant), 1.5);
  const auto samples = estimator_samples(log, steps.nominal.model, kArm4Pads);
  const auto sigma = calibrate_sigma(steps, samples, log.source);
  const EstimatorTrace with_bands = replay_estimator(steps, samples);
  const int alarm = calibrate_torque_alarm(with_bands);
  EXPECT_EQ(p.static_dead_band, steps.parameters.static_dead_band);
  EXPECT_EQ(p.skin.detector.on_level_kpa, steps.parameters.skin.detector.on_level_kpa);
  EXPECT_EQ(p.skin.force_gain, steps.parameters.skin.force_gain);
  EXPECT_EQ(p.nominal_sigma, sigma.nominal);
  EXPECT_EQ(p.fused_sigma, sigma.fused);
  EXPECT_EQ(p.torque_alarm_samples, alarm);
  EXPECT_EQ(p.compensator_speed_limit, speed_envelope(samples));
  EXPECT_EQ(p.compensator_acceleration_limit, acceleration_envelope(with_bands));
  // The twin's excitation moves every joint, but gently: the network never saw a hard stop.
  for (int j = 0; j < kArm4Joints; ++j) {
    EXPECT_GT(p.compensator_acceleration_limit[j], 0.1) << "joint " << j + 1;
    EXPECT_LT(p.compensator_acceleration_limit[j], 50.0) << "joint " << j + 1;
  }

  // The compensator was used: it removes most of the transition error on every joint (measured,
  // simulated, 60 s: fused 13–85 mA against nominal 66–339 mA).
  for (int j = 0; j < kArm4Joints; ++j)
    EXPECT_LT(p.fused_sigma[j], 0.6 * p.nominal_sigma[j]) << "joint " << j + 1;
  // The contact-free log has short excursions outside the bands: a single one must not alarm.
  EXPECT_GT(p.torque_alarm_samples, 1);

  const auto file = std::filesystem::temp_directory_path() /
                    ("tpf_arm_calibration_" + std::to_string(::getpid()) + ".json");
  save_estimator_parameters(file, p, log.source);
  const ArmParameters read = load_estimator_parameters(file, kArm4Joints);
  std::filesystem::remove(file);
  EXPECT_EQ(read.fused_sigma, p.fused_sigma);
  EXPECT_EQ(read.static_dead_band, p.static_dead_band);
  EXPECT_EQ(read.torque_alarm_samples, p.torque_alarm_samples);
  EXPECT_EQ(read.compensator_acceleration_limit, p.compensator_acceleration_limit);
}

// The acceleration envelope is of the q̈ the estimator computes: the sample's own where it has
// one (here), skipping rows the estimator skips (a NaN sample must not widen the domain).
TEST(AccelerationEnvelope, IsTheLargestAccelerationTheEstimatorUsesPerJoint) {
  ReplaySetup setup;
  setup.nominal = load_nominal_model(data("arm4.params.json"), data("arm4.robot.json"));
  setup.pads = load_pads(data("arm4.pads.json"), setup.nominal.model);
  SensorNoise noise;
  noise.effort.setConstant(kArm4Joints, 0.025);  // N·m
  noise.effort_step.setConstant(kArm4Joints, 0.005);
  noise.pad_kpa = 0.05;
  setup.parameters = estimator_parameters_from_noise(noise, 1.5);
  std::vector<ReplaySample> samples(4);
  const double accelerations[4][kArm4Joints] = {
      {0.5, -1.0, 0.0, 2.0}, {-3.0, 0.25, 0.0, -1.5}, {1.0, 1.0, 0.0, 1.0}, {99, 99, 99, 99}};
  for (int k = 0; k < 4; ++k) {
    ReplaySample& s = samples[static_cast<std::size_t>(k)];
    s.resize(kArm4Joints, kArm4Pads);
    s.t = 0.0025 * k;
    s.q << 0.1, 0.3, 0.4, 0.1;
    s.dq.setZero();
    s.effort.setZero();
    s.pressure.setZero(kArm4Pads);
    s.has_ddq = true;
    for (int j = 0; j < kArm4Joints; ++j)
      s.ddq[j] = accelerations[k][j];
  }
  samples[3].q[0] = std::numeric_limits<double>::quiet_NaN();  // skipped by the estimator
  const auto a = acceleration_envelope(replay_estimator(setup, samples));
  EXPECT_DOUBLE_EQ(a[0], 3.0);
  EXPECT_DOUBLE_EQ(a[1], 1.0);
  EXPECT_DOUBLE_EQ(a[2], 0.0);
  EXPECT_DOUBLE_EQ(a[3], 2.0);
}

}  // namespace
}  // namespace tpf::offline
