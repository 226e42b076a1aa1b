// A 6-axis arm with a coupled wrist, logged by the twin and identified held out by time: the
// Kinova Gen3's chain cut at its 6th joint (tip spherical_wrist_2_link; the bracelet folded
// into it at q7 = 0) whose motor 6 turns with q₅ + q₆ ("coupled_to": {"joint_5": 1.0}). The
// twin's friction (LuGre on each motor's velocity (C·q̇)_m, a Stribeck excess, no load terms) is
// the Gen3's of its first six joints. identify with the coupled robot file is compared per joint
// with plain least squares of the model class with the coupling, fitted on the same training rows
// and scored on the same held-out moving rows: the rigid-body base parameters of
// compute_regressor (armature per motor through C) + per-motor Coulomb and viscous friction on
// (C·q̇)_m through Cᵀ. The same log identified with the uncoupled robot file is clearly worse on
// the wrist.
//
// Measured (seed 5, 60 s at 400 Hz): held-out moving RMS of identify / of the model-class fit
// 0.907, 0.978, 0.788, 0.483 on joints 1–4 and 0.964, 1.012 on the wrist (5, 6); over seeds 1–8
// 0.40–1.001 on joints 1–4 and 0.77–1.035 on the wrist. identify's Stribeck curves fit the twin's
// friction excess the Coulomb + viscous class leaves in its residual, most on joint 4. Without
// the coupling the wrist's held-out RMS is 3.6× (joint 5) and 2.4× (joint 6) that of the coupled
// fit (2.4–5.5× over seeds 1–8), while joints 1–4 of the coupled fit are 1.004, 1.001, 1.004,
// 0.991 of its (bar: 1.02).
//
// Over seeds 1–8, joints 1–4 of the coupled file against the uncoupled one, the worst joint per
// seed: 1.008, 1.060, 1.059, 1.030, 1.004, 1.032, 1.013, 1.144 (seed 8, joint 2). Neither the
// joint weights nor the Stribeck stage make these (on seed 8 the coupled file's weights improve
// the uncoupled fit's joint 2, and the curves take 0.02 N·m off joint 2 in both): the uncoupled
// fit's wrist error takes its M(q) below the inertia prior's floor on every seed, so identify
// chooses a prior for it, while the coupled fit's M(q) stays above the floor on seeds 2, 6 and 8
// and is left without one; on seeds 3 and 4 both take one, of strengths each within 1 % of its
// own best held-out error (0.1 against 1, 1 against 5.6). On the twin the prior's mean is the
// simulated arm itself, so the prior lowers joints 1–4's held-out error (seed 8, joint 2: 0.171
// → 0.151 N·m in the linear fit at strength 1). With the prior off on both files the ratios are
// 0.56–1.085 over seeds 1–8, 14 of 32 above 1: the variance of a 15 s held-out window. Seed 8 is
// asserted so (second test).
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "offline/identify/identify.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/heldout_moving_rms.hpp"
#include "support/temp_dir.hpp"
#include "tpf/dynamics/regressor.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

constexpr int kWristArmJoints = 6;
using WristVector = Eigen::Matrix<double, kWristArmJoints, 1>;

// Writes gen3.urdf (the Gen3's), wrist6.friction.json, wrist6_coupled.robot.json and
// wrist6.robot.json (the same drives without coupled_to) into `dir`.
void write_wrist_arm_files(const TempDir& dir) {
  std::filesystem::copy_file(std::string(TPF_TEST_DATA_DIR) + "/real/kinova-gen3/gen3.urdf",
                             dir / "gen3.urdf");
  std::ofstream(dir / "wrist6.friction.json") << R"({
  "effort_unit": "N*m",
  "coulomb":           [1.20, 1.20, 1.20, 1.20, 0.50, 0.50],
  "static":            [1.60, 1.60, 1.60, 1.60, 0.70, 0.70],
  "stribeck_velocity": [0.030, 0.030, 0.030, 0.030, 0.040, 0.040],
  "stribeck_exponent": [1.5, 1.5, 1.5, 1.5, 1.5, 1.5],
  "viscous":           [3.0, 3.0, 3.0, 3.0, 1.2, 1.2],
  "load_coulomb":      [0, 0, 0, 0, 0, 0],
  "load_viscous":      [0, 0, 0, 0, 0, 0],
  "bristle_stiffness": [2.0e4, 2.0e4, 2.0e4, 2.0e4, 8.0e3, 8.0e3],
  "bristle_damping":   [150.0, 150.0, 150.0, 150.0, 50.0, 50.0]
})";
  const auto robot = [](bool coupled) {
    std::string text = R"({"format": "tpf-robot", "version": 1, "name": "gen3_wrist6",
  "urdf": "gen3.urdf", "friction": "wrist6.friction.json", "tip_link": "spherical_wrist_2_link",
  "gravity": [0, 0, -9.81], "joints": [)";
    for (int j = 1; j <= kWristArmJoints; ++j) {
      const bool large = j <= 4;
      text += std::string(j > 1 ? ",\n" : "\n") + R"(    {"name": "joint_)" + std::to_string(j) +
              R"(", "gear_ratio": 100.0, "rotor_inertia": )" + (large ? "1e-05" : "4e-06") +
              R"(, "torque_constant": )" + (large ? "9.13" : "5.852") + R"(, "current_limit": )" +
              (large ? "10000" : "6000");
      if (coupled && j == 6) text += R"(, "coupled_to": {"joint_5": 1.0})";
      text += "}";
    }
    return text + "]}";
  };
  std::ofstream(dir / "wrist6_coupled.robot.json") << robot(true);
  std::ofstream(dir / "wrist6.robot.json") << robot(false);
}

// Held-out RMS per joint over the held-out moving samples where `residual` is finite.
WristVector wrist_heldout_rms(const offline::JointSamples& s, const Eigen::MatrixXd& residual) {
  const HeldOutMovingRms heldout = heldout_moving_rms(s, residual);
  for (int j = 0; j < kWristArmJoints; ++j)
    EXPECT_GT(heldout.samples[j], 1000) << "joint " << j + 1 << ": too few held-out moving samples";
  return heldout.rms;
}

// Plain least squares of the model class with the coupling on the training moving rows of
// `s`: the regressor's rigid-body base columns (inertial + per-motor armature) and its per-motor
// Coulomb and viscous columns (Cᵀ·(τ_c sgn θ̇ + b θ̇), θ̇ = C·q̇). Its residual per sample.
Eigen::MatrixXd wrist_reference_residual(const offline::JointSamples& s,
                                         const Model<double, Eigen::Dynamic>& model) {
  const int n = model.joint_count();
  std::vector<int> columns = rigid_body_base_parameters(model).independent;
  for (int c = 11 * n; c < 13 * n; ++c)
    columns.push_back(c);
  const auto p = static_cast<Eigen::Index>(columns.size());
  Data<double, Eigen::Dynamic> data(model);
  Regressor<double, Eigen::Dynamic> Y;
  Eigen::MatrixXd r(n, p);
  const auto rows_at = [&](Eigen::Index k) {
    compute_regressor(model, data, Eigen::VectorXd(s.q.row(k).transpose()),
                      Eigen::VectorXd(s.dq.row(k).transpose()),
                      Eigen::VectorXd(s.ddq.row(k).transpose()), Y);
    for (Eigen::Index c = 0; c < p; ++c)
      r.col(c) = Y.col(columns[static_cast<std::size_t>(c)]);
    return r;
  };
  std::vector<Eigen::VectorXd> a;
  std::vector<double> b;
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    if (!s.valid[k] || s.heldout[k]) continue;
    rows_at(k);
    for (int j = 0; j < n; ++j)
      if (moving_sample(s, j, k)) {
        a.push_back(r.row(j).transpose());
        b.push_back(s.effort(k, j));
      }
  }
  Eigen::MatrixXd A(static_cast<Eigen::Index>(a.size()), p);
  Eigen::VectorXd B(A.rows());
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    A.row(i) = a[static_cast<std::size_t>(i)].transpose();
    B[i] = b[static_cast<std::size_t>(i)];
  }
  const Eigen::VectorXd theta = A.colPivHouseholderQr().solve(B);
  Eigen::MatrixXd residual = Eigen::MatrixXd::Constant(s.size(), n, std::nan(""));
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s.valid[k])
      residual.row(k) = (s.effort.row(k).transpose() - rows_at(k) * theta).transpose();
  return residual;
}

// 60 s of the twin's excitation of the coupled arm (400 Hz), seed `seed`.
offline::Log wrist_arm_log(const TempDir& dir, std::uint64_t seed) {
  offline::Scenario s = offline::default_scenario((dir / "wrist6_coupled.robot.json").string());
  s.kind = offline::Scenario::Kind::kExcitation;
  s.initial_q = offline::twin_vector({0.0, 0.4, 0.0, 1.5, 0.0, 0.6});
  s.excitation.lower = offline::twin_vector({-2.0, -1.2, -2.0, -2.2, -2.0, -1.8});
  s.excitation.upper = offline::twin_vector({2.0, 1.2, 2.0, 2.2, 2.0, 1.8});
  s.excitation.speed_min = 0.05;
  s.excitation.speed_max = 0.8;
  return offline::simulate_to_log(s, seed, 60.0);
}

TEST(CoupledWristArm, IdentifyMatchesTheModelClassHeldOutOnEveryJoint) {
  const TempDir dir("coupled_wrist");
  write_wrist_arm_files(dir);
  const offline::Log log = wrist_arm_log(dir, 5);

  const auto coupled = load_robot<double, Eigen::Dynamic>(dir / "wrist6_coupled.robot.json");
  ASSERT_TRUE(coupled.coupled);
  ASSERT_EQ(coupled.coupling(5, 4), 1.0);
  const offline::Identification id = offline::identify(log, coupled);
  const offline::JointSamples& samples = id.samples;
  const WristVector fitted = wrist_heldout_rms(samples, id.residual);
  const WristVector reference =
      wrist_heldout_rms(samples, wrist_reference_residual(samples, coupled));

  const auto uncoupled = load_robot<double, Eigen::Dynamic>(dir / "wrist6.robot.json");
  const offline::Identification plain = offline::identify(log, uncoupled);
  const WristVector without = wrist_heldout_rms(plain.samples, plain.residual);
  for (int j = 0; j < kWristArmJoints; ++j)
    std::printf(
        "joint %d: held-out moving RMS identify %.4f, model-class least squares %.4f (ratio "
        "%.3f), identify without the coupling %.4f N·m\n",
        j + 1, fitted[j], reference[j], fitted[j] / reference[j], without[j]);
  const auto& f = id.nominal.friction;
  for (int m = 0; m < kWristArmJoints; ++m)
    std::printf("motor %d: τ_c %.3f b %.3f\n", m + 1, f.coulomb[m], f.viscous[m]);

  for (int j = 0; j < kWristArmJoints; ++j)
    EXPECT_LE(fitted[j], 1.2 * reference[j]) << "joint " << j + 1;
  // Joints 1–4 are no worse with the coupling than without it (measured 1.004, 1.001, 1.004,
  // 0.991 of the uncoupled file's) where both fits take the inertia prior (strength 1 each).
  EXPECT_GT(id.inertia_prior.judged_strength, 0.0);
  EXPECT_GT(plain.inertia_prior.judged_strength, 0.0);
  for (int j = 0; j < 4; ++j)
    EXPECT_LE(fitted[j], 1.02 * without[j]) << "joint " << j + 1;
  for (int j = 4; j < kWristArmJoints; ++j)
    EXPECT_GT(without[j], 2.0 * fitted[j]) << "joint " << j + 1;
}

// Seed 8, where identify's defaults leave joint 2 of the coupled file 1.144× the uncoupled
// file's: the coupled fit's M(q) is above the floor, so identify leaves it without the inertia
// prior, while the uncoupled fit's wrist error takes its M(q) below the floor and brings in the
// prior (strength 1) that, on the twin, pulls joints 1–4 toward the very inertias it simulates.
// With the prior off on both the coupling costs joints 1–4 nothing: measured 1.009, 0.965,
// 1.016, 0.992 of the uncoupled file's.
TEST(CoupledWristArm, WithoutThePriorJointsOneToFourAreNoWorseOnSeed8) {
  const TempDir dir("coupled_wrist_seed8");
  write_wrist_arm_files(dir);
  const offline::Log log = wrist_arm_log(dir, 8);
  offline::IdentifyOptions options;
  options.inertia_prior = false;
  const offline::Identification id = offline::identify(
      log, load_robot<double, Eigen::Dynamic>(dir / "wrist6_coupled.robot.json"), options);
  const offline::Identification plain = offline::identify(
      log, load_robot<double, Eigen::Dynamic>(dir / "wrist6.robot.json"), options);
  const WristVector fitted = wrist_heldout_rms(id.samples, id.residual);
  const WristVector without = wrist_heldout_rms(plain.samples, plain.residual);
  for (int j = 0; j < kWristArmJoints; ++j)
    std::printf(
        "joint %d: held-out moving RMS without the prior, coupled %.4f, uncoupled %.4f "
        "N·m (ratio %.3f)\n",
        j + 1, fitted[j], without[j], fitted[j] / without[j]);
  for (int j = 0; j < 4; ++j)
    EXPECT_LE(fitted[j], 1.02 * without[j]) << "joint " << j + 1;
  for (int j = 4; j < kWristArmJoints; ++j)
    EXPECT_GT(without[j], 2.0 * fitted[j]) << "joint " << j + 1;
}

}  // namespace
}  // namespace tpf::test
