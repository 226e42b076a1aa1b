// The per-cycle nominal model (link form, Newton–Euler on one forward kinematics) against the
// regressor form it replaces: equal to 1e-9 on random states, also for parameter sets that are
// not physical, and allocation-free.
#include "tpf/estimation/link_parameters.hpp"

#include <gtest/gtest.h>

#include <random>

#include "estimation/twin_fixture.hpp"
#include "support/allocation_counter.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::test {
namespace {

struct State {
  Vec q, dq, ddq;
};

State random_state(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  State s;
  for (int j = 0; j < kJoints; ++j) {
    s.q[j] = 3.0 * u(rng);
    s.dq[j] = 2.0 * u(rng);
    s.ddq[j] = 10.0 * u(rng);
  }
  if (u(rng) > 0.6) s.dq[static_cast<int>((u(rng) + 1.0) * 1.99)] = 0.0;  // sgn(0) = 0 case
  return s;
}

/// The twin's nominal model with load-dependent friction and the base values replaced by random
/// numbers (a link "mass" may then be negative: the link form must not care), plus Coulomb and
/// viscous regressor columns of two joints among the base columns.
NominalModel<double, kJoints> scrambled_nominal(std::mt19937_64& rng) {
  NominalModel<double, kJoints> n = twin_nominal();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n.base_count; ++i)
    n.base_values[i] *= 1.0 + 0.5 * u(rng);
  n.base_values[0] = -0.7;
  n.base_columns[n.base_count] = 11 * kJoints + 1;  // f_c of joint 2
  n.base_values[n.base_count++] = 0.3;
  n.base_columns[n.base_count] = 12 * kJoints + 3;  // f_v of joint 4
  n.base_values[n.base_count++] = 0.05;
  n.friction.load_coulomb = Vec(2.0, 1.0, 3.0, 0.5);
  n.friction.load_viscous = Vec(0.5, 0.1, 0.2, 0.3);
  return n;
}

TEST(LinkParameters, PredictEffortEqualsTheRegressorFormOnRandomStates) {
  std::mt19937_64 rng(7);
  for (const bool scrambled : {false, true}) {
    NominalModel<double, kJoints> nominal = scrambled ? scrambled_nominal(rng) : twin_nominal();
    if (!scrambled) {  // and the branch without load-dependent friction
      nominal.friction.load_coulomb.setZero();
      nominal.friction.load_viscous.setZero();
    }
    const NominalLinks<double, kJoints> links = nominal_links(nominal);
    EXPECT_EQ(links.load_dependent, scrambled);
    ArmData fast(nominal.model), reference(nominal.model);
    for (int n = 0; n < 300; ++n) {
      const State s = random_state(rng);
      Vec rigid, friction, rigid_ref, friction_ref;
      predict_effort(nominal, links, fast, s.q, s.dq, s.ddq, rigid, friction);
      predict_effort_by_regressor(nominal, reference, s.q, s.dq, s.ddq, rigid_ref, friction_ref);
      // 1e-9 relative to the largest torque (or 1 N·m).
      const double scale = std::max(1.0, rigid_ref.cwiseAbs().maxCoeff());
      EXPECT_LT((rigid - rigid_ref).cwiseAbs().maxCoeff(), 1e-9 * scale) << "state " << n;
      EXPECT_LT((friction - friction_ref).cwiseAbs().maxCoeff(), 1e-9 * scale) << "state " << n;
      // The link poses the estimator reuses for the pads are those of q.
      for (int k = 1; k <= kJoints; ++k)
        EXPECT_LT((fast.oMi[k].p - reference.oMi[k].p).norm(), 1e-15);
    }
  }
}

TEST(LinkParameters, ModelInertiasReproduceRneaAndGravity) {
  std::mt19937_64 rng(3);
  const LinkParameters<double, kJoints> links = link_parameters<double, kJoints>(
      dynamic_parameters(arm(), Vec::Constant(0.2).eval(), Vec::Constant(0.1).eval()));
  ArmData data(arm()), reference(arm());
  for (int n = 0; n < 100; ++n) {
    const State s = random_state(rng);
    forward_kinematics(arm(), data, s.q);
    const Vec tau = link_parameter_torque(arm(), links, data, s.dq, s.ddq);
    const Vec sign = s.dq.unaryExpr([](double v) { return double((v > 0) - (v < 0)); });
    const Vec expected = rnea(arm(), reference, s.q, s.dq, s.ddq) + 0.2 * sign + 0.1 * s.dq;
    EXPECT_LT((tau - expected).cwiseAbs().maxCoeff(), 1e-12) << "state " << n;
    const Vec g = link_parameter_gravity(arm(), links, data);
    EXPECT_LT((g - compute_gravity(arm(), reference, s.q)).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(LinkParameters, PerCyclePathAllocatesNothing) {
  std::mt19937_64 rng(5);
  const NominalModel<double, kJoints> nominal = scrambled_nominal(rng);
  const NominalLinks<double, kJoints> links = nominal_links(nominal);
  ArmData data(nominal.model);
  std::vector<State> states;
  for (int n = 0; n < 100; ++n)
    states.push_back(random_state(rng));
  Vec rigid, friction, sum = Vec::Zero();
  AllocationCounter counter;
  for (const State& s : states) {
    predict_effort(nominal, links, data, s.q, s.dq, s.ddq, rigid, friction);
    sum += rigid + friction;
  }
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(sum.allFinite());
}

}  // namespace
}  // namespace tpf::test
