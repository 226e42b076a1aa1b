// Identification and diagnosis of an arm beyond the project's robot files: a random 9-joint arm,
// logged from a known nominal model (its robot file's rigid body and a Stribeck friction per
// joint, small effort noise). identify recovers the friction and predicts the held-out blocks to
// the noise; diagnose on the same clean log claims no effect.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "offline/diagnose/diagnose.hpp"
#include "offline/identify/identify.hpp"
#include "support/random_arm.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

constexpr int kNine = 9;
constexpr double kNoise = 0.02;  ///< std of the effort noise [N·m]

/// The robot file's model of a random 9-joint arm (joint limits ±3 rad, drives of ratio 100).
Model<double, Eigen::Dynamic> nine_joint_robot() {
  return make_model<double, Eigen::Dynamic>(robot_description_of(random_arm(kNine, 19)));
}

/// The truth: the robot file's rigid body and a Stribeck + viscous friction per joint.
NominalModelX nine_joint_truth(const Model<double, Eigen::Dynamic>& model) {
  StribeckParameters<double, Eigen::Dynamic> friction;
  friction.resize(kNine);
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int j = 0; j < kNine; ++j) {
    friction.coulomb[j] = 0.8 + 1.2 * u(rng);
    friction.static_friction[j] = 1.4 * friction.coulomb[j];
    friction.stribeck_velocity[j] = 0.05 + 0.05 * u(rng);
    friction.viscous[j] = 0.4 + 0.6 * u(rng);
  }
  return nominal_from_model(model, friction);
}

/// An excitation log of `truth` (tau<j> in N·m, 200 Hz): every joint a sum of three sines of its
/// own frequencies, within ±1.1 rad; effort = rigid body + friction + Gaussian noise.
offline::Log nine_joint_log(const NominalModelX& truth, double seconds) {
  offline::Log log;
  log.source = "nine_joint.csv";
  log.columns = {"t"};
  for (const char* prefix : {"q", "dq", "ddq", "tau"})
    for (int j = 1; j <= kNine; ++j)
      log.columns.push_back(prefix + std::to_string(j));
  const double rate = 200.0;
  const auto n = static_cast<Eigen::Index>(seconds * rate);
  log.values.resize(n, 1 + 4 * kNine);
  std::mt19937_64 rng(29);
  std::normal_distribution<double> noise(0.0, kNoise);
  Data<double, Eigen::Dynamic> data(truth.model);
  Eigen::VectorXd q(kNine), dq(kNine), ddq(kNine), rigid, friction;
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / rate;
    for (int j = 0; j < kNine; ++j) {
      q[j] = dq[j] = ddq[j] = 0.0;
      for (int h = 0; h < 3; ++h) {
        const double w = 0.43 + 0.29 * j + 0.97 * h, a = 0.6 / (1.0 + h);
        const double phase = 0.7 * j + 1.3 * h;
        q[j] += a * std::sin(w * t + phase);
        dq[j] += a * w * std::cos(w * t + phase);
        ddq[j] -= a * w * w * std::sin(w * t + phase);
      }
    }
    predict_effort_by_regressor(truth, data, q, dq, ddq, rigid, friction);
    log.values(k, 0) = t;
    for (int j = 0; j < kNine; ++j) {
      log.values(k, 1 + j) = q[j];
      log.values(k, 1 + kNine + j) = dq[j];
      log.values(k, 1 + 2 * kNine + j) = ddq[j];
      log.values(k, 1 + 3 * kNine + j) = rigid[j] + friction[j] + noise(rng);
    }
  }
  return log;
}

TEST(NineJointArm, IdentifyRecoversTheFrictionAndPredictsTheHeldOutBlocksToTheNoise) {
  const Model<double, Eigen::Dynamic> model = nine_joint_robot();
  const NominalModelX truth = nine_joint_truth(model);
  const offline::Log log = nine_joint_log(truth, 120.0);
  const offline::Identification id = offline::identify(log, model);
  ASSERT_EQ(id.nominal.model.joint_count(), kNine);
  EXPECT_TRUE(id.consistency.consistent())
      << (id.consistency.problems.empty() ? "" : id.consistency.problems.front());
  const StribeckParameters<double, Eigen::Dynamic>& f = id.nominal.friction;
  for (int j = 0; j < kNine; ++j) {
    const double rmse = id.heldout[static_cast<std::size_t>(j)][offline::Regime::Moving].rmse;
    std::printf(
        "joint %d: held-out moving RMSE %.4f N·m (noise %.3f); Coulomb %.4f (true %.4f), viscous "
        "%.4f (true %.4f), static %.4f (true %.4f)\n",
        j + 1, rmse, kNoise, f.coulomb[j], truth.friction.coulomb[j], f.viscous[j],
        truth.friction.viscous[j], f.static_friction[j], truth.friction.static_friction[j]);
    EXPECT_LT(rmse, 1.25 * kNoise) << "joint " << j + 1;
    EXPECT_NEAR(f.coulomb[j], truth.friction.coulomb[j], 0.03 * truth.friction.coulomb[j])
        << "joint " << j + 1;
    EXPECT_NEAR(f.viscous[j], truth.friction.viscous[j], 0.03 * truth.friction.viscous[j])
        << "joint " << j + 1;
  }
}

TEST(NineJointArm, DiagnoseClaimsNoEffectOnACleanLog) {
  const Model<double, Eigen::Dynamic> model = nine_joint_robot();
  const offline::Log log = nine_joint_log(nine_joint_truth(model), 90.0);
  const offline::Diagnosis d = offline::diagnose(log, model);
  ASSERT_EQ(d.joints(), kNine);
  for (const std::string& finding : d.findings)
    std::printf("  %s\n", finding.c_str());
  EXPECT_TRUE(d.selected.empty());
  EXPECT_TRUE(d.claims.empty());
  EXPECT_FALSE(d.cad_payload.claimed) << d.cad_payload.mass << " kg";
  EXPECT_EQ(d.nominal.model.joint_count(), kNine);
}

}  // namespace
}  // namespace tpf::test
