// Training features are what the run-time estimator computes; the target is effort −
// predict_effort. Twin logs are SIMULATED.
#include "offline/compensator_training/training_dataset.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "offline/compensator_training/tcn_parameters.hpp"
#include "offline/pipeline/declared_model.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/arm_fixture.hpp"
#include "support/constants.hpp"
#include "tpf/nn/load_tcn_weights.hpp"

namespace tpf::offline {
namespace {

using test::data_path;
using test::kArm4Joints;
using test::kArm4Pads;
using Vec = JointVector<double, kArm4Joints>;
using AllJointsTcn = tpf::AllJointsTcn<kAllJointsHidden>::For<double, kArm4Joints>;

const Log& excitation_log() {
  static const Log log = [] {
    Log l = simulate_to_log(load_scenario(data_path("scenarios/excitation.json")), 7, 12.0);
    l.source = "excitation seed 7 (simulated)";
    return l;
  }();
  return log;
}

ReplaySetup twin_setup() {
  ReplaySetup s;
  s.nominal =
      (declared_nominal_model(data_path("arm4.robot.json"), data_path("arm4.friction.json")));
  s.pads = load_pads(data_path("arm4.pads.json"), s.nominal.model);
  s.parameters = estimator_parameters_from_noise(
      estimate_sensor_noise(excitation_log(), s.nominal.model.torque_constant));
  return s;
}

TEST(TrainingFeatures, EqualTheEstimatorsOwnComputationRowByRow) {
  const ReplaySetup setup = twin_setup();
  const auto samples = estimator_samples(excitation_log(), setup.nominal.model, kArm4Pads);
  const EstimatorTrace trace = replay_estimator(setup, samples);
  ASSERT_EQ(trace.rows(), excitation_log().rows());
  EXPECT_EQ(trace.contact.maxCoeff(), 0) << "no pad may switch on in a contact-free log";

  // Independent re-computation with the documented trainer recipe: acceleration filter,
  // predict_effort, StaticFrictionTracker with contact = false, compensator_input with the
  // nominal friction of predict_effort.
  AccelerationFilter<double, kArm4Joints> filter(setup.parameters.acceleration_cutoff_hz,
                                                 setup.parameters.acceleration_damping);
  StaticFrictionTracker<double, kArm4Joints> tracker(setup.parameters.static_friction);
  // The trainer's recipe at the arm's fixed joint count.
  const NominalModel<double, kArm4Joints> nominal = joint_count_cast<kArm4Joints>(setup.nominal);
  Data<double, kArm4Joints> data(nominal.model);
  double t_prev = std::numeric_limits<double>::quiet_NaN();
  int moving_rows = 0, static_rows = 0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const ReplaySample& s = samples[k];
    const auto r = static_cast<Eigen::Index>(k);
    if (k == 0) filter.reset(s.dq);
    const double h = k == 0 ? setup.parameters.sample_period_s : s.t - t_prev;
    t_prev = s.t;
    const Vec ddq = filter.update(s.dq, h);
    Vec rigid, friction;
    predict_effort(nominal, data, s.q, s.dq, ddq, rigid, friction);
    const Vec residual = s.effort - rigid - friction;
    tracker.update(s.t, s.dq, residual, false, std::numeric_limits<double>::infinity(),
                   Vec::Zero());
    const auto x = compensator_input<double, kArm4Joints>(s.q, s.dq, ddq,
                                                          tracker.friction_estimate(), friction);
    ASSERT_LT((trace.inputs.row(r).transpose() - x).cwiseAbs().maxCoeff(), 1e-9) << "row " << k;
    ASSERT_LT((trace.residual.row(r).transpose() - residual).cwiseAbs().maxCoeff(), 1e-9);
    for (int j = 0; j < kArm4Joints; ++j)
      (tracker.is_static(j) ? static_rows : moving_rows)++;
  }
  EXPECT_GT(static_rows, 1000);  // the log holds both rests and moves
  EXPECT_GT(moving_rows, 1000);
}

TEST(TrainingFeatures, TargetIsTheResidualInNewtonMetresAndJointColumnsArePicked) {
  const ReplaySetup setup = twin_setup();
  const EstimatorTrace trace =
      replay_estimator(setup, estimator_samples(excitation_log(), setup.nominal.model, kArm4Pads));
  const TcnSequence all = training_sequence(trace);
  ASSERT_EQ(all.inputs.cols(), 20);
  ASSERT_EQ(all.residual.cols(), 4);
  for (int j = 0; j < kArm4Joints; ++j) {
    EXPECT_EQ(all.residual.col(j), trace.residual.col(j));
    const TcnSequence one = training_sequence(trace, j);
    ASSERT_EQ(one.inputs.cols(), 5);
    for (int c = 0; c < 5; ++c)
      EXPECT_EQ(one.inputs.col(c), trace.inputs.col(c * kArm4Joints + j));
    EXPECT_LT((one.residual.col(0) - all.residual.col(j)).cwiseAbs().maxCoeff(), 1e-12);
  }
  EXPECT_THROW(training_sequence(trace, 4), Error);
}

TEST(TrainingFeatures, RegimeWeightsMarkRestAndTheBreakAwayWindow) {
  // A hand-made trace at 400 Hz: joint 0 rests 0.1 s then moves; joint 1 moves throughout.
  EstimatorTrace trace;
  const Eigen::Index rows = 200;
  trace.t = Eigen::VectorXd::LinSpaced(rows, 0.0, (rows - 1) * 0.0025);
  trace.dq = Eigen::MatrixXd::Constant(rows, 2, 0.01);
  trace.dq.col(0).head(40).setZero();
  trace.dq(100, 0) = std::numeric_limits<double>::quiet_NaN();
  RegimeOptions regimes;
  regimes.fallback_transition_s = 0.0688;  // rows k0 … k0 + 27 (27 · 2.5 ms < 68.8 ms)
  const Eigen::MatrixXd w = regime_weights(trace, -1, 2.0, 10.0, regimes);
  ASSERT_EQ(w.rows(), rows);
  ASSERT_EQ(w.cols(), 2);
  for (Eigen::Index k = 0; k < rows; ++k) {
    const double expected = k < 40 ? 2.0 : k < 40 + 28 ? 10.0 : 1.0;
    EXPECT_EQ(w(k, 0), expected) << "row " << k;
    EXPECT_EQ(w(k, 1), 1.0) << "row " << k;
  }
  const Eigen::MatrixXd one = regime_weights(trace, 0, 2.0, 10.0, regimes);
  ASSERT_EQ(one.cols(), 1);
  EXPECT_EQ(one.col(0), w.col(0));
  EXPECT_THROW(regime_weights(trace, 2, 1.0, 1.0), Error);
}

TEST(TrainingFeatures, ScaledHeadsScaleTheStreamingOutputExactly) {
  TcnArchitecture a;
  a.inputs = AllJointsTcn::Input::RowsAtCompileTime;
  a.outputs = 4;
  TcnParameters p = init_tcn_parameters(a, 3);
  p.input_mean = Eigen::VectorXd::LinSpaced(a.inputs, -1.0, 1.0);
  p.input_std = Eigen::VectorXd::LinSpaced(a.inputs, 0.5, 2.0);
  TcnParameters scaled = p;
  const Eigen::Vector4d scale(208.0, 210.0, 350.0, 1.0);
  scale_tcn_outputs(scaled, scale);
  auto plain = std::make_unique<AllJointsTcn>(), big = std::make_unique<AllJointsTcn>();
  const TcnWeightFile fp = to_weight_file(p), fs = to_weight_file(scaled);
  tcn_weights_from_file(fp, *plain);
  tcn_weights_from_file(fs, *big);
  plain->reset(AllJointsTcn::Input::Zero());
  big->reset(AllJointsTcn::Input::Zero());
  for (int k = 0; k < 60; ++k) {
    const AllJointsTcn::Input x = AllJointsTcn::Input::Constant(0.1 * k).array().sin();
    const Eigen::Vector4d y = plain->step(x), z = big->step(x);
    EXPECT_LT((z - scale.cwiseProduct(y)).cwiseAbs().maxCoeff(), 1e-9 * (1 + z.norm()));
  }
}

TEST(TrainingFeatures, MaskedInputIsIgnoredAndExactWhereItWasHeldAtZero) {
  using JointTcn = Tcn<double, kCompensatorInputsPerJoint, 16, 4>;
  TcnArchitecture a;
  a.inputs = kCompensatorInputsPerJoint;
  a.hidden = 16;
  TcnParameters p = init_tcn_parameters(a, 5);
  p.input_mean = Eigen::VectorXd::LinSpaced(a.inputs, -1.0, 1.0);
  p.input_std = Eigen::VectorXd::LinSpaced(a.inputs, 0.5, 2.0);
  p.input_mean[0] = 0.0;  // as the trainer normalises a channel held at 0
  p.input_std[0] = 1.0;
  TcnParameters masked = p;
  mask_tcn_inputs(masked, {0});
  auto plain = std::make_unique<JointTcn>(), without = std::make_unique<JointTcn>(),
       shifted = std::make_unique<JointTcn>();
  tcn_weights_from_file(to_weight_file(p), *plain);
  tcn_weights_from_file(to_weight_file(masked), *without);
  tcn_weights_from_file(to_weight_file(masked), *shifted);
  plain->reset(JointTcn::Input::Zero());
  without->reset(JointTcn::Input::Zero());
  JointTcn::Input steady = JointTcn::Input::Zero();
  steady[0] = 2.0;  // only q differs
  shifted->reset(steady);
  double moved = 0.0;
  for (int k = 0; k < 80; ++k) {
    JointTcn::Input x = JointTcn::Input::LinSpaced(0.1 * k, 0.3 * k + 1.0).array().sin();
    x[0] = 0.0;
    // Where q was held at 0 (the training data), masking changes nothing.
    EXPECT_EQ(without->step(x)[0], plain->step(x)[0]);
    // Any other q: the masked network's output is the same, bit for bit.
    JointTcn::Input y = x;
    y[0] = 3.0 * std::sin(0.7 * k) + 2.0;
    EXPECT_EQ(shifted->step(y)[0], without->output()[0]);
    moved = std::max(moved, std::abs(plain->output()[0]));
  }
  EXPECT_GT(moved, 0.0);
  // The unmasked network does move with q, so the checks above can fail.
  auto seeing = std::make_unique<JointTcn>();
  tcn_weights_from_file(to_weight_file(p), *seeing);
  JointTcn::Input x = JointTcn::Input::Constant(0.5);
  seeing->reset(x);
  const double at_zero = seeing->step(x)[0];
  x[0] = 2.0;
  EXPECT_NE(seeing->step(x)[0], at_zero);

  EXPECT_THROW(mask_tcn_inputs(masked, {kCompensatorInputsPerJoint}), Error);
  TcnArchitecture square = a;
  square.hidden = a.inputs;  // no input projection: its identity skip would still pass q
  TcnParameters no_projection = init_tcn_parameters(square, 1);
  EXPECT_THROW(mask_tcn_inputs(no_projection, {0}), Error);
}

TEST(TrainingFeatures, WeightFilesOfTheOldFourInputSizeAreRefusedNamingTheFile) {
  // Per-joint files written before τ_fric,nom joined the input (4 inputs per joint).
  const auto dir =
      std::filesystem::temp_directory_path() / ("tpf_training_old_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  TcnArchitecture old;
  old.inputs = 4;
  old.hidden = kPerJointHiddenSmall;
  old.levels = kCompensatorLevels;
  for (int j = 0; j < kArm4Joints; ++j)
    write_tcn_weight_file(joint_weight_path(dir / "old.json", j).string(),
                          to_weight_file(init_tcn_parameters(old, 1)));
  try {
    find_compensator_weights(dir / "old.json", kArm4Joints);
    ADD_FAILURE() << "a 4-input weight file was accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(joint_weight_path(dir / "old.json", 0).string()), std::string::npos)
        << message;
    EXPECT_NE(message.find("architecture.inputs: 4 in the file, 5 expected"), std::string::npos)
        << message;
  }
  // The all-joints file of the old size (16 inputs) likewise.
  old.inputs = 4 * kArm4Joints;
  old.hidden = kAllJointsHidden;
  old.outputs = kArm4Joints;
  write_tcn_weight_file((dir / "all.json").string(), to_weight_file(init_tcn_parameters(old, 1)));
  try {
    find_compensator_weights(dir / "all.json", kArm4Joints);
    ADD_FAILURE() << "a 16-input all-joints file was accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find((dir / "all.json").string()), std::string::npos) << message;
    EXPECT_NE(message.find("architecture.inputs: 16 in the file, 20 expected"), std::string::npos)
        << message;
  }
  std::filesystem::remove_all(dir);
}

TEST(TrainingFeatures, SamplesRefuseAWrongJointCount) {
  Log log;
  log.source = "three.csv";
  log.columns = {"t", "q1", "q2", "q3", "dq1", "dq2", "dq3", "i1", "i2", "i3"};
  log.values = Eigen::MatrixXd::Zero(2, 10);
  EXPECT_THROW(
      estimator_samples(log, load_robot<double, Eigen::Dynamic>(data_path("arm4.robot.json")),
                        kArm4Pads),
      Error);
}

}  // namespace
}  // namespace tpf::offline
