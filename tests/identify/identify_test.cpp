// Identification on twin logs: the true rigid body and friction are recovered where identifiable.
#include "offline/identify/identify.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/arm_fixture.hpp"
#include "tpf/friction/friction_file.hpp"

namespace tpf::test {
namespace {

using offline::Regime;

offline::Log twin_log(double duration, std::uint64_t seed) {
  auto scenario = offline::load_scenario(data_path("scenarios/excitation.json"));
  return offline::simulate_to_log(scenario, seed, duration);
}

TEST(Identify, RecoversTheTwinsRigidBodyAndFrictionOnHeldOutData) {
  const offline::Log log = twin_log(150.0, 11);
  const offline::Identification id =
      offline::identify(log, joint_count_cast<Eigen::Dynamic>(arm()));
  const NominalModel<double, kJoints> identified = joint_count_cast<kJoints>(id.nominal);
  const auto& s = id.samples;
  EXPECT_EQ(s.units.unit, EffortUnit::Milliampere);
  // The fit is in N·m; this test compares in mA, as the log and its gt_fric hold it.
  const Vec ma = current_from_torque(arm(), Vec::Ones().eval());
  EXPECT_TRUE(id.consistency.consistent());
  // The truth: the robot file's rigid body (the twin has no payload here) and its friction file.
  const auto truth = nominal_from_model<kJoints>(
      arm(), load_stribeck_parameters<double, kJoints>(data_path("arm4.friction.json")));
  ArmData d1, d2;
  Eigen::VectorXd se_rigid = Eigen::VectorXd::Zero(kJoints), ss_rigid = se_rigid;
  Eigen::VectorXd se_fric = se_rigid, ss_fric = se_rigid;
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    if (!s.valid[k] || !s.heldout[k]) continue;
    const Vec q = s.q.row(k).transpose(), dq = s.dq.row(k).transpose();
    const Vec ddq = s.ddq.row(k).transpose();
    Vec r1, f1, r2, f2;
    predict_effort(identified, d1, q, dq, ddq, r1, f1);
    predict_effort(truth, d2, q, dq, ddq, r2, f2);
    r1 = r1.cwiseProduct(ma), f1 = f1.cwiseProduct(ma), r2 = r2.cwiseProduct(ma);
    for (int j = 0; j < kJoints; ++j) {
      se_rigid[j] += std::pow(r1[j] - r2[j], 2);
      ss_rigid[j] += r2[j] * r2[j];
      if (s.regimes[j][k] == Regime::Moving && std::abs(dq[j]) > 0.1) {
        const double gt = log.col("gt_fric" + std::to_string(j + 1))[k];
        se_fric[j] += std::pow(f1[j] - gt, 2);
        ss_fric[j] += gt * gt;
      }
    }
  }
  for (int j = 0; j < kJoints; ++j) {
    const double rigid_error = std::sqrt(se_rigid[j] / ss_rigid[j]);
    const double friction_error = std::sqrt(se_fric[j] / ss_fric[j]);
    std::printf(
        "joint %d: rigid error %.3f %%, friction error %.3f %% (held-out), moving RMSE %.1f mA\n",
        j + 1, 100 * rigid_error, 100 * friction_error, id.heldout[j][Regime::Moving].rmse * ma[j]);
    // Within 3 % of the rigid torque, or within the current noise (6 mA) on the light wrist.
    const double count = static_cast<double>(s.size()) / 4.0;
    EXPECT_LT(std::sqrt(se_rigid[j] / count), std::max(0.03 * std::sqrt(ss_rigid[j] / count), 8.0))
        << "joint " << j + 1 << " rigid error " << rigid_error;
    EXPECT_LT(friction_error, 0.10) << "joint " << j + 1;
  }
}

/// On a log that excites every inertia, M(q) is positive definite well above the floor the
/// inertia prior guards, so the prior (on by default) changes nothing: the same model, bit for bit.
TEST(Identify, TheInertiaPriorLeavesAWellExcitedFitAlone) {
  const offline::Log log = twin_log(30.0, 12);
  offline::IdentifyOptions options;
  const auto model = joint_count_cast<Eigen::Dynamic>(arm());
  const offline::Identification with = offline::identify(log, model, options);
  options.inertia_prior = false;
  const offline::Identification plain = offline::identify(log, model, options);
  EXPECT_EQ(with.inertia_prior.judged_strength, 0.0);
  EXPECT_EQ(with.inertia_prior.written_strength, 0.0);
  EXPECT_GT(with.inertia_prior.written_min_eigenvalue, 0.0);
  EXPECT_EQ(with.nominal.base_values, plain.nominal.base_values);
  EXPECT_EQ(with.nominal.friction.coulomb, plain.nominal.friction.coulomb);
  EXPECT_EQ(with.nominal.friction.stribeck_velocity, plain.nominal.friction.stribeck_velocity);
}

}  // namespace
}  // namespace tpf::test
