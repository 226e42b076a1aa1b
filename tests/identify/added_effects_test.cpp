// Each added effect is one typed object: the columns diagnose fits (its basis functions, via the
// offline family that writes it) times the coefficients written into a nominal model are the
// run-time torque of that model, and each effect's parameter-file fields round-trip.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <random>

#include "offline/effects/effect_columns.hpp"
#include "support/arm_fixture.hpp"

namespace tpf::test {
namespace {

using VecX = Eigen::VectorXd;

/// arm()'s 4 joints as a run-time-size vector.
VecX arm_vector(double a, double b, double c, double d) {
  return Eigen::Vector4d(a, b, c, d);
}

/// Ripple frequencies on every joint, so both ripple families are offered everywhere.
offline::CandidateInputs ripple_inputs() {
  offline::CandidateInputs inputs;
  inputs.enabled = true;
  inputs.ripple_cycles = Eigen::VectorXd::LinSpaced(kJoints, 3.0, 9.0);
  inputs.ripple_motor_cycles = Eigen::VectorXd::LinSpaced(kJoints, 1.0, 2.5);
  return inputs;
}

/// A model with nothing added and no friction: its prediction less the rigid body is the added
/// effects' torque.
NominalModelX bare_model() {
  NominalModelX nominal;
  nominal.model = joint_count_cast<Eigen::Dynamic>(arm());
  nominal.resize(kJoints);
  nominal.model.gear_ratio = arm_vector(100.0, 120.0, 80.0, 50.0);
  return nominal;
}

/// Random coefficients θ_j of family Family for every joint j, written into `nominal` through
/// Family::write (as diagnose writes a fit); returns them.
template <typename Family>
std::vector<std::vector<double>> write_random(NominalModelX& nominal, std::mt19937_64& rng,
                                              const offline::CandidateInputs& inputs, int columns) {
  StribeckParameters<double, Eigen::Dynamic> linear;
  linear.resize(kJoints);
  Eigen::VectorXd payload = Eigen::VectorXd::Zero(11 * kJoints);
  const BaseParameters base;
  offline::WrittenModel written{nominal, linear, payload, base, inputs, false};
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::vector<std::vector<double>> theta(kJoints, std::vector<double>(columns));
  for (int j = 0; j < kJoints; ++j) {
    for (double& x : theta[j])
      x = u(rng);
    Family::write(theta[j].data(), j, written);
  }
  return theta;
}

/// At random states, Family's columns of joint j times the coefficients θ_j written for it are
/// the run-time torque of joint j (τ_j = φ_j·θ_j), and remove_group takes it out again.
template <typename Family>
void expect_columns_times_coefficients_are_the_torque(int columns) {
  std::mt19937_64 rng(7);
  const offline::CandidateInputs inputs = ripple_inputs();
  const std::vector<int> no_base_columns;
  const offline::JointSamples no_samples;
  const Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(kJoints, 13 * kJoints);
  const VecX at_rest = VecX::Zero(kJoints);
  for (int trial = 0; trial < 20; ++trial) {
    NominalModelX nominal = bare_model();
    const auto theta = write_random<Family>(nominal, rng, inputs, columns);
    const VecX q = random_vector<kJoints>(rng, 3.0), dq = random_vector<kJoints>(rng, 2.0),
               ddq = random_vector<kJoints>(rng, 5.0);
    const offline::SampleRow row{{q, dq, ddq, nominal.model.gear_ratio},
                                 Y,
                                 at_rest,
                                 at_rest,
                                 no_base_columns,
                                 inputs,
                                 no_samples,
                                 0};
    const VecX tau = added_effort(nominal, q, dq, ddq);
    for (int j = 0; j < kJoints; ++j) {
      std::vector<double> phi(columns);
      Family::fill(row, j, phi.data());
      double expected = 0;
      for (int c = 0; c < columns; ++c)
        expected += phi[c] * theta[j][c];
      EXPECT_NEAR(tau[j], expected, 1e-12 * (1 + std::abs(expected))) << Family::key << " j" << j;
    }
    offline::FeatureGroup group;
    group.key = Family::key;
    for (group.joint = 0; group.joint < kJoints; ++group.joint)
      offline::remove_group(group, nominal);
    EXPECT_EQ(added_effort(nominal, q, dq, ddq), VecX::Zero(kJoints)) << Family::key << " removed";
  }
}

TEST(NominalModel, SpringColumnsTimesCoefficientsAreItsRunTimeTorque) {
  expect_columns_times_coefficients_are_the_torque<offline::SpringColumns>(1);
}
TEST(NominalModel, OffsetColumnsTimesCoefficientsAreItsRunTimeTorque) {
  expect_columns_times_coefficients_are_the_torque<offline::OffsetColumns>(1);
}
TEST(NominalModel, CouplingColumnsTimesCoefficientsAreItsRunTimeTorque) {
  expect_columns_times_coefficients_are_the_torque<offline::CouplingColumns>(2 * (kJoints - 1));
}
TEST(NominalModel, RippleColumnsTimesCoefficientsAreItsRunTimeTorque) {
  expect_columns_times_coefficients_are_the_torque<offline::OutputRippleColumns>(2);
  expect_columns_times_coefficients_are_the_torque<offline::MotorRippleColumns>(2);
}

TEST(NominalModel, EachAddedEffectIsTheTorqueItsHeaderStates) {
  const VecX q = arm_vector(0.3, -0.7, 1.1, 0.2), dq = arm_vector(0.5, -1.5, 0.25, 2.0),
             ddq = arm_vector(-3.0, 1.0, 4.0, -0.5);
  NominalModelX nominal = bare_model();
  auto torque_of = [&](const NominalModelX& m) { return added_effort(m, q, dq, ddq); };
  NominalModelX spring = nominal;
  spring.added.get<JointSpring>().stiffness[2] = 3.0;
  EXPECT_EQ(torque_of(spring), arm_vector(0, 0, 3.0 * 1.1, 0));
  NominalModelX offset = nominal;
  offset.added.get<JointOffset>().offset[1] = -0.4;
  EXPECT_EQ(torque_of(offset), arm_vector(0, -0.4, 0, 0));
  NominalModelX coupling = nominal;
  coupling.added.get<MotionCoupling>().velocity(0, 3) = 0.5;
  coupling.added.get<MotionCoupling>().acceleration(0, 2) = 0.25;
  coupling.added.get<MotionCoupling>().acceleration(3, 1) = -2.0;
  const VecX expected = arm_vector(0.5 * 2.0 + 0.25 * 4.0, 0, 0, -2.0 * 1.0);
  EXPECT_LT((torque_of(coupling) - expected).norm(), 1e-15);
  NominalModelX ripple = nominal;
  ripple.added.get<PositionRipple>().add({1, 3.0, true, 0.2, -0.1});
  const double phase = 3.0 * 120.0 * -0.7;  // n·G·q on the motor side
  const double tau = 0.2 * std::sin(phase) - 0.1 * std::cos(phase);
  EXPECT_LT((torque_of(ripple) - arm_vector(0, tau, 0, 0)).norm(), 1e-12);
}

/// Family's random coefficients written, saved, loaded: the same torque at random states (and the
/// file names only the fields the effects own).
template <typename Family>
void expect_round_trip(int columns) {
  std::mt19937_64 rng(11);
  NominalModelX nominal = bare_model();
  write_random<Family>(nominal, rng, ripple_inputs(), columns);
  // The file's robot (gear ratios as the robot file has them) and its rigid body: a file
  // without one is refused.
  const NominalModelX robot_file =
      nominal_from_model(joint_count_cast<Eigen::Dynamic>(arm()), nominal.friction);
  nominal.model = robot_file.model;
  nominal.base_count = robot_file.base_count;
  nominal.base_columns = robot_file.base_columns;
  nominal.base_values = robot_file.base_values;
  const auto path = std::filesystem::temp_directory_path() /
                    ("tpf_effects_" + std::to_string(::getpid()) + ".json");
  save_nominal_model(path, nominal);
  const NominalModelX loaded = load_nominal_model(path, data_path("arm4.robot.json"));
  std::filesystem::remove(path);
  for (int s = 0; s < 20; ++s) {
    const VecX q = random_vector<kJoints>(rng, 3.0), dq = random_vector<kJoints>(rng, 2.0),
               ddq = random_vector<kJoints>(rng, 5.0);
    const VecX expected = added_effort(nominal, q, dq, ddq);
    EXPECT_GT(expected.norm(), 0.0);
    EXPECT_LT((added_effort(loaded, q, dq, ddq) - expected).norm(), 1e-12 * (1 + expected.norm()))
        << Family::key;
  }
}

TEST(NominalModel, EachAddedEffectRoundTripsThroughAParameterFile) {
  expect_round_trip<offline::SpringColumns>(1);
  expect_round_trip<offline::OffsetColumns>(1);
  expect_round_trip<offline::CouplingColumns>(2 * (kJoints - 1));
  expect_round_trip<offline::OutputRippleColumns>(2);
  expect_round_trip<offline::MotorRippleColumns>(2);
}

}  // namespace
}  // namespace tpf::test
