// The nominal model at a run-time joint count: the loaders return it for any arm, it predicts the
// same efforts as the fixed-count model a controller converts it to, and a 9-joint arm's model
// goes through its parameter file and back.
#include <gtest/gtest.h>

#include <random>

#include "support/arm_fixture.hpp"
#include "support/random_arm.hpp"
#include "support/temp_dir.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/friction/friction_file.hpp"

namespace tpf::test {
namespace {

constexpr int X = Eigen::Dynamic;
const TempDir kFiles("nominal_run_time");

Eigen::VectorXd random_vector(std::mt19937_64& rng, int n, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(n);
  for (int j = 0; j < n; ++j)
    v[j] = u(rng);
  return v;
}

/// arm4's model with one effect of each kind and load-dependent friction: every term of
/// predict_effort is in use.
NominalModel<double, kJoints> arm4_with_effects() {
  auto nominal = nominal_from_model<kJoints>(
      arm(), load_stribeck_parameters<double, kJoints>(data_path("arm4.friction.json")));
  nominal.added.get<JointSpring>().stiffness[1] = 40.0;
  nominal.added.get<JointOffset>().offset[2] = -5.0;
  nominal.added.get<PositionRipple>().add({3, 12.0, true, 3.0, -1.0});
  nominal.added.get<MotionCoupling>().acceleration(0, 2) = 0.7;
  nominal.friction.neighbour_load_coulomb(1, 2) = 0.05;
  return nominal;
}

TEST(NominalModelRunTimeSize, PredictsTheEffortOfTheFixedCountModel) {
  const auto fixed = arm4_with_effects();
  const auto file = kFiles / "arm4.params.json";
  save_nominal_model(file, fixed, "test");
  const NominalModelX any = load_nominal_model(file, data_path("arm4.robot.json"));
  ASSERT_EQ(any.model.joint_count(), kJoints);
  EXPECT_EQ(any.base_count, fixed.base_count);
  Data<double, X> any_data(any.model);
  ArmData fixed_data;
  std::mt19937_64 rng(7);
  for (int s = 0; s < 20; ++s) {
    const Vec q = random_vector(rng, kJoints, 2.0), dq = random_vector(rng, kJoints, 1.0),
              ddq = random_vector(rng, kJoints, 3.0);
    Vec rigid, friction;
    predict_effort(fixed, fixed_data, q, dq, ddq, rigid, friction);
    Eigen::VectorXd any_rigid, any_friction;
    predict_effort(any, any_data, Eigen::VectorXd(q), Eigen::VectorXd(dq), Eigen::VectorXd(ddq),
                   any_rigid, any_friction);
    EXPECT_LT((any_rigid - rigid).norm(), 1e-12 * (1.0 + rigid.norm())) << "state " << s;
    EXPECT_LT((any_friction - friction).norm(), 1e-12 * (1.0 + friction.norm())) << "state " << s;
  }
  // The controller's conversion gives back the fixed model's numbers exactly.
  const auto back = joint_count_cast<kJoints>(any);
  EXPECT_EQ(back.base_values, fixed.base_values);
  EXPECT_EQ(back.added.get<MotionCoupling>().acceleration,
            fixed.added.get<MotionCoupling>().acceleration);
  EXPECT_EQ(back.added.get<PositionRipple>().count, 1);
}

TEST(NominalModelRunTimeSize, NineJointModelRoundTripsThroughItsFile) {
  const Model<double, X> model = random_arm(9, 11);
  const RobotDescription robot = robot_description_of(model);
  StribeckParameters<double, X> friction;
  friction.resize(9);
  std::mt19937_64 rng(3);
  friction.coulomb = random_vector(rng, 9, 1.0).cwiseAbs();
  friction.static_friction = friction.coulomb * 1.5;
  friction.viscous = random_vector(rng, 9, 0.5).cwiseAbs();
  NominalModelX nominal = nominal_from_model(make_model<double, X>(robot), friction);
  nominal.added.get<JointSpring>().stiffness[8] = 12.0;
  nominal.added.get<MotionCoupling>().velocity(8, 0) = 0.3;
  nominal.added.get<PositionRipple>().add({8, 30.65, false, 0.2, 0.1});
  const auto file = kFiles / "random9.params.json";
  save_nominal_model(file, nominal, "test");
  const NominalModelX loaded = load_nominal_model(file, robot);
  ASSERT_EQ(loaded.model.joint_count(), 9);
  EXPECT_EQ(loaded.base_count, nominal.base_count);

  // The true model's rigid part is the model's own inverse dynamics (armature included): the base
  // parameters of nine links reproduce RNEA, and the added effects add what they state.
  Data<double, X> data(loaded.model), reference(loaded.model);
  for (int s = 0; s < 10; ++s) {
    const Eigen::VectorXd q = random_vector(rng, 9, 2.5), dq = random_vector(rng, 9, 1.0),
                          ddq = random_vector(rng, 9, 3.0);
    Eigen::VectorXd rigid, friction_torque;
    predict_effort(loaded, data, q, dq, ddq, rigid, friction_torque);
    Eigen::VectorXd expected = rnea(loaded.model, reference, q, dq, ddq);
    expected[8] +=
        12.0 * q[8] + 0.3 * dq[0] + 0.2 * std::sin(30.65 * q[8]) + 0.1 * std::cos(30.65 * q[8]);
    EXPECT_LT((rigid - expected).norm(), 1e-8 * expected.norm()) << "state " << s;
    Eigen::VectorXd by_regressor_rigid, by_regressor_friction;
    predict_effort_by_regressor(loaded, reference, q, dq, ddq, by_regressor_rigid,
                                by_regressor_friction);
    EXPECT_LT((by_regressor_rigid - rigid).norm(), 1e-9 * rigid.norm());
    EXPECT_LT((by_regressor_friction - friction_torque).norm(), 1e-12);
  }
}

TEST(NominalModelRunTimeSize, AProgramOfAnotherJointCountIsRefused) {
  const auto file = kFiles / "arm4-for-7.params.json";
  save_nominal_model(file, arm4_with_effects(), "test");
  try {
    load_nominal_model<7>(file, data_path("arm4.robot.json"));
    ADD_FAILURE() << "a 4-joint model was loaded by a 7-joint program";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("4 joints"), std::string::npos) << message;
    EXPECT_NE(message.find("asks for 7"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace tpf::test
