// The fast forms (joint rotations by Rodrigues' formula on the model's constants, link inertias
// about their origins precomputed, the gravity-only pass, the symmetric parallel-axis update) give
// the textbook forms' numbers to rounding, on the 4-DoF arm and the 7-DoF Kinova Gen3; so does
// the regressor, whose joints take each link's wrench through their axes carried up the chain.
#include <gtest/gtest.h>

#include <random>

#include "reference_dynamics.hpp"
#include "support/arm_fixture.hpp"

namespace tpf::test {
namespace {

constexpr double kRounding = 1e-12;

template <int N>
void expect_fast_forms_match_reference(const Model<double, N>& model, unsigned seed) {
  Data<double, N> data;
  reference::Workspace<N> ref;
  Regressor<double, N> Y;
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < 50; ++trial) {
    const auto q = random_vector<N>(rng, 3.0), dq = random_vector<N>(rng, 2.0),
               ddq = random_vector<N>(rng, 5.0);
    forward_kinematics(model, data, q);
    reference::kinematics(model, ref, q);
    for (int k = 1; k <= N; ++k) {
      EXPECT_LT((data.liMi[k].R - ref.liMi[k].R).norm(), kRounding);
      EXPECT_LT((data.oMi[k].R - ref.oMi[k].R).norm(), kRounding);
      EXPECT_LT((data.oMi[k].p - ref.oMi[k].p).norm(), kRounding);
      EXPECT_LT((data.axis_world[k] - ref.oMi[k].R * model.axes[k - 1]).norm(), kRounding);
    }
    EXPECT_LT((rnea(model, data, q, dq, ddq) - reference::rnea(model, q, dq, ddq)).norm(),
              kRounding);
    const JointVector<double, N> zero = JointVector<double, N>::Zero();
    EXPECT_LT((compute_gravity(model, data, q) - reference::rnea(model, q, zero, zero)).norm(),
              kRounding);
    EXPECT_LT((compute_mass_matrix(model, data, q) - reference::mass_matrix(model, q)).norm(),
              kRounding);
    compute_regressor(model, data, q, dq, ddq, Y);
    const Regressor<double, N> Y_ref = reference::regressor(model, q, dq, ddq);
    EXPECT_LT((Y - Y_ref).cwiseAbs().maxCoeff(), kRounding * (1.0 + Y_ref.cwiseAbs().maxCoeff()));
  }
}

TEST(ModelConstants, FastFormsMatchTheTextbookFormsOnTheArm) {
  expect_fast_forms_match_reference(arm(), 81);
}

TEST(ModelConstants, FastFormsMatchTheTextbookFormsOnTheGen3) {
  expect_fast_forms_match_reference(
      load_robot<double, 7>(data_path("real/kinova-gen3/gen3.robot.json")), 82);
}

TEST(ModelConstants, GravityIsTheTorqueThatHoldsTheArmStill) {
  // A dedicated pass, so check it against the full dynamics of a state at rest too: RNEA with
  // q̇ = q̈ = 0 through the library's own Newton–Euler passes.
  ArmData data;
  RandomStates rs(83);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec q = rs.vector(3.0);
    const Vec g = compute_gravity(arm(), data, q);
    EXPECT_LT((g - rnea(arm(), data, q, Vec::Zero(), Vec::Zero())).norm(), kRounding);
    EXPECT_GT(g.norm(), 0.1);  // the arm's links are heavy enough to need holding
  }
}

TEST(ModelConstants, EditingAnInertiaNeedsUpdateConstants) {
  Arm model = arm();
  EXPECT_TRUE(model.constants_current());
  model.inertias[kJoints].mass += 0.5;  // a payload
  EXPECT_FALSE(model.constants_current());
  model.update_constants();
  EXPECT_TRUE(model.constants_current());
  ArmData data;
  const Vec q = RandomStates(84).vector(2.0);
  const Vec zero = Vec::Zero();
  EXPECT_LT((compute_gravity(model, data, q) - reference::rnea(model, q, zero, zero)).norm(),
            kRounding);
  const Vec with_payload = compute_gravity(model, data, q);
  EXPECT_GT((with_payload - compute_gravity(arm(), data, q)).norm(), 0.1);
}

}  // namespace
}  // namespace tpf::test
