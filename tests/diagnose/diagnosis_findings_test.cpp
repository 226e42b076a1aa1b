// What diagnose says is left unexplained: the moving held-out error against the effort's noise in
// motion (not the quieter noise at rest), and a hint at the effort's unit where the error is
// thousands of times the noise.
#include "offline/diagnose/diagnosis_findings.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "offline/diagnose/residual_analysis.hpp"

namespace tpf::test {
namespace {

/// A diagnosis of two joints with nothing selected: held-out moving RMSE `moving` per joint, noise
/// at rest `rest` and in motion `in_motion` [N·m].
offline::EffectDiagnosis diagnosis(const Eigen::Vector2d& moving, const Eigen::Vector2d& rest,
                                   const Eigen::Vector2d& in_motion) {
  offline::EffectDiagnosis d;
  d.samples.units.torque_constant = Eigen::Vector2d::Ones();
  d.samples.t = Eigen::VectorXd::LinSpaced(2, 0.0, 1.0);
  d.samples.valid = {1, 1};
  d.samples.heldout = {1, 0};
  d.noise_floor = rest;
  d.motion_noise = in_motion;
  d.model_band_hz = 15;
  d.before.resize(2);
  d.after.resize(2);
  d.written_before.resize(2);  // default: NaN statistics, nothing worsened
  d.written_after.resize(2);
  for (int j = 0; j < 2; ++j) {
    d.after[j][2] = {100.0, 0.0, 100.0 * moving[j] * moving[j]};
    d.after[j][0] = {100.0, 0.0, 100.0 * rest[j] * rest[j]};
    d.before[j] = d.after[j];
  }
  return d;
}

std::vector<std::string> unexplained(const offline::EffectDiagnosis& d, int joint) {
  std::vector<std::string> out;
  for (const std::string& f : offline::diagnosis_findings(d, {}))
    if (f.find("Left unexplained on joint " + std::to_string(joint) + ": moving") == 0)
      out.push_back(f);
  return out;
}

TEST(DiagnosisFindings, TheMovingErrorIsComparedWithTheNoiseInMotion) {
  // Joint 1 moves with 8× the noise it has at rest, and its error is that noise: nothing is left
  // unexplained. Joint 2's error is 5× its noise in motion: it is.
  const auto d = diagnosis({8.0, 5.0}, {1.0, 0.5}, {8.0, 1.0});
  EXPECT_TRUE(unexplained(d, 1).empty());
  const auto joint2 = unexplained(d, 2);
  ASSERT_EQ(joint2.size(), 1u);
  EXPECT_NE(joint2[0].find("5.0× the effort's noise in motion (1, above the model's 15 Hz band; "
                           "0.5 at rest)"),
            std::string::npos)
      << joint2[0];
  EXPECT_EQ(joint2[0].find("unit"), std::string::npos) << joint2[0];
}

TEST(DiagnosisFindings, AnErrorThousandsOfTimesTheNoiseHintsAtTheUnit) {
  const auto d = diagnosis({2368.0, 5.0}, {1.0, 1.0}, {1.5, 1.0});
  const auto joint1 = unexplained(d, 1);
  ASSERT_EQ(joint1.size(), 1u);
  EXPECT_NE(joint1[0].find("An error 2368× the noise"), std::string::npos) << joint1[0];
  EXPECT_NE(joint1[0].find("unit the log declares"), std::string::npos) << joint1[0];
}

TEST(DiagnosisFindings, TheNoiseInMotionIsTheEffortAboveTheModelsBand) {
  // 1 kHz, joint 1 moving: a 1 Hz swing (the model's band) plus ±0.3 alternating noise (500 Hz);
  // at rest the effort is still. The noise in motion is the noise's RMS, 0.3, not the swing.
  offline::JointSamples s;
  const int n = 4000;
  s.units.torque_constant = Eigen::VectorXd::Ones(1);
  s.t = Eigen::VectorXd::LinSpaced(n, 0.0, (n - 1) * 1e-3);
  s.q = s.dq = s.ddq = s.effort = Eigen::MatrixXd::Zero(n, 1);
  s.regimes.assign(1, std::vector<offline::Regime>(n, offline::Regime::Moving));
  s.valid.assign(n, 1);
  s.heldout.assign(n, 0);
  for (int k = 0; k < n; ++k) {
    s.q(k, 0) = 0.5 * std::sin(2 * M_PI * s.t[k]);
    s.effort(k, 0) = 5 * std::sin(2 * M_PI * s.t[k]) + (k % 2 ? 0.3 : -0.3);
  }
  for (int k = 3000; k < n; ++k) {
    s.regimes[0][k] = offline::Regime::Static;
    s.effort(k, 0) = 0.0;
  }
  const offline::ResidualAnalysis a = offline::analyse_residual(
      s, s.effort, Eigen::MatrixXd::Zero(n, 1), Eigen::VectorXd::Ones(1), 15.0);
  EXPECT_NEAR(a.motion_noise[0], 0.3, 0.02);
  EXPECT_NEAR(a.noise_floor[0], 0.0, 1e-12);
}

}  // namespace
}  // namespace tpf::test
