// diagnose starts from identify's result: on a log where no effect is added, its written model is
// identify's (the same base parameters and friction, the same held-out error), and every fit of
// the diagnosis has identify's joint weights and inertia prior strengths.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "offline/diagnose/diagnose.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/arm_fixture.hpp"
#include "tpf/common/error.hpp"

namespace tpf::test {
namespace {

offline::Log clean_log() {
  auto scenario = offline::load_scenario(data_path("scenarios/excitation.json"));
  scenario.effects.load_dependent_friction = false;
  return offline::simulate_to_log(scenario, 21, 60.0);
}

void expect_relatively_equal(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    EXPECT_NEAR(a[i], b[i], 1e-9 * std::max(std::abs(b[i]), 1e-12)) << what << " " << i;
}

TEST(DiagnoseFromIdentify, WithNothingAddedItWritesIdentifysModel) {
  const offline::Log log = clean_log();
  const offline::ModelX model = joint_count_cast<Eigen::Dynamic>(arm());
  // Each from the log, as `tpf identify` and `tpf diagnose` run.
  const offline::Identification id = offline::identify(log, model);
  const offline::Diagnosis d = offline::diagnose(log, model);
  for (const offline::Claim& c : d.claims)
    ASSERT_FALSE(c.written) << d.groups[c.groups[0]].title;
  ASSERT_TRUE(id.refitted);
  EXPECT_TRUE(d.refitted);
  expect_relatively_equal(d.nominal.base_values, id.nominal.base_values, "written base value");
  expect_relatively_equal(d.judged.base_values, id.judged.base_values, "judged base value");
  expect_relatively_equal(d.declared.base_values, id.judged.base_values, "declared base value");
  expect_relatively_equal(d.nominal.friction.coulomb, id.nominal.friction.coulomb, "Coulomb");
  expect_relatively_equal(d.nominal.friction.viscous, id.nominal.friction.viscous, "viscous");
  expect_relatively_equal(d.nominal.friction.load_coulomb, id.nominal.friction.load_coulomb,
                          "load Coulomb");
  EXPECT_EQ(d.inertia_prior.judged_strength, id.inertia_prior.judged_strength);
  EXPECT_EQ(d.inertia_prior.written_strength, id.inertia_prior.written_strength);
  for (int j = 0; j < kJoints; ++j)
    for (const offline::Regime r :
         {offline::Regime::Static, offline::Regime::StaticToKinetic, offline::Regime::Moving}) {
      const double identified = id.heldout[j][r].rmse;
      EXPECT_NEAR(d.written_after[j][r].rmse, identified, 1e-9 * identified) << j << " " << int(r);
      EXPECT_NEAR(d.written_before[j][r].rmse, identified, 1e-9 * identified) << j << " " << int(r);
    }
}

TEST(DiagnoseFromIdentify, RefusesTheIdentificationOfOtherSamples) {
  const offline::Log log = clean_log();
  const offline::ModelX model = joint_count_cast<Eigen::Dynamic>(arm());
  const offline::DiagnoseOptions options;
  offline::IdentificationSetup setup = offline::prepare_diagnosis(log, model, options.samples);
  const BaseParameters base = setup.base;
  const auto regressors = setup.regressors;
  const auto abs_gravity = setup.abs_gravity;
  offline::Identification id = offline::identify(log, model, std::move(setup), {});
  id.residual.conservativeResize(id.residual.rows() - 1, Eigen::NoChange);
  EXPECT_THROW(
      offline::diagnose(log, model, {std::move(id.samples), base, regressors, abs_gravity, nullptr},
                        id, options),
      Error);
}

}  // namespace
}  // namespace tpf::test
