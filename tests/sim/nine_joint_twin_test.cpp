// The twin on a robot of more joints than any shipped one: tests/sim/arm9 (9 joints, a different
// drive and friction on every joint, six pads). The logged physics is checked against tpf::core
// evaluated with the robot file's own parameters:
//   K_t·i = RNEA(q, q̇, q̈) + τ_f        on every moving joint, τ_f the friction file's Stribeck
//                                        curve, K_t the robot file's torque constant
//   K_t·i = G(q) + τ_f − τ_ext          at rest under the hand's pushes, τ_ext = J_padᵀ·F
// A twin that took another joint's drive or friction, dropped the armature, mixed up joints or
// mapped a pad's force through the wrong Jacobian misses these by far more than the sensor noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "tpf/dynamics/rnea.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/kinematics/forward_kinematics.hpp"
#include "tpf/kinematics/point_jacobian.hpp"
#include "tpf/model/load_robot.hpp"
#include "tpf/model/robot_description.hpp"
#include "tpf/skin/pad_layout.hpp"

namespace {

using namespace tpf::offline;

constexpr int kArm9Joints = 9;
constexpr int kArm9Pads = 6;

std::string arm9_file(const std::string& name) {
  return std::string(TPF_SIM_TEST_DIR "/arm9/") + name;
}

// The values of `prefix`1 … `prefix`9 in row k.
TwinVector arm9_row(const Log& log, const char* prefix, Eigen::Index k) {
  TwinVector v(kArm9Joints);
  for (int j = 0; j < kArm9Joints; ++j)
    v[j] = log.col(indexed_name(prefix, j + 1))(k);
  return v;
}

TEST(NineJointTwin, LoadsWithEveryPerJointVectorSizedForNineJoints) {
  const Scenario s = load_scenario(arm9_file("arm9-excitation.json"));
  EXPECT_EQ(s.joints, kArm9Joints);
  EXPECT_EQ(s.initial_q.size(), kArm9Joints);
  EXPECT_EQ(s.excitation.lower.size(), kArm9Joints);
  EXPECT_EQ(s.effects.coupling.matrix.rows(), kArm9Joints);
  EXPECT_EQ(s.friction_file, arm9_file("arm9.friction.json"));
  EXPECT_EQ(simulation_columns(s).size(), 1 + 7 * kArm9Joints + kArm9Pads + 4);
}

// Excitation with the memoryless Stribeck friction (the LuGre bristles' state is not in the log),
// checked row by row against RNEA and the friction file; positions stay inside the joint limits.
TEST(NineJointTwin, CurrentIsRigidBodyTorquePlusTheFilesFrictionOverTheFilesTorqueConstant) {
  Scenario s = load_scenario(arm9_file("arm9-excitation.json"));
  s.effects.friction = EffectsConfig::Friction::kStribeck;
  const Log log = simulate_to_log(s, 91, 30.0);
  ASSERT_GT(log.rows(), 11000);

  const tpf::RobotDescription robot = tpf::load_robot_description(s.robot_file);
  const auto model = tpf::load_robot<double, Eigen::Dynamic>(s.robot_file);
  tpf::Data<double, Eigen::Dynamic> data(model);
  const auto friction = tpf::load_stribeck_parameters(s.friction_file, kArm9Joints);
  TwinVector kt(kArm9Joints);
  for (int j = 0; j < kArm9Joints; ++j)
    kt[j] = robot.drives[static_cast<std::size_t>(j)].torque_constant;

  // Residuals K_t·i − (RNEA + τ_f), N·m: moving joints against the file's curve, resting joints
  // against the logged (static) friction; and the logged friction against the curve. The noise
  // they are held to: the current's, 6 mA white plus 1 mA rounding, times the joint's K_t.
  TwinVector moving_sq = TwinVector::Zero(kArm9Joints), resting_sq = moving_sq,
             logged_sq = moving_sq, torque_sq = moving_sq;
  std::vector<long> moving(kArm9Joints, 0), resting(kArm9Joints, 0);
  double worst_moving = 0.0;  // mA
  for (Eigen::Index k = 0; k < log.rows(); ++k) {
    const TwinVector q = arm9_row(log, "q", k), dq = arm9_row(log, "dq", k);
    const TwinVector ddq = arm9_row(log, "gt_ddq", k);
    for (int j = 0; j < kArm9Joints; ++j) {
      ASSERT_GE(q[j], model.lower[j]) << "joint " << j + 1 << ", row " << k;
      ASSERT_LE(q[j], model.upper[j]) << "joint " << j + 1 << ", row " << k;
    }
    const TwinVector g = tpf::compute_gravity(model, data, q);
    const TwinVector tau = tpf::rnea(model, data, q, dq, ddq);
    const TwinVector motor = kt.cwiseProduct(arm9_row(log, "i", k)) / 1000.0;
    const TwinVector logged_friction = kt.cwiseProduct(arm9_row(log, "gt_fric", k)) / 1000.0;
    for (int j = 0; j < kArm9Joints; ++j) {
      torque_sq[j] += motor[j] * motor[j];
      if (std::abs(dq[j]) > 0.05) {
        const double curve = tpf::stribeck_friction(friction, j, dq[j], std::abs(g[j]));
        const double e = motor[j] - (tau[j] + curve);
        moving_sq[j] += e * e;
        worst_moving = std::max(worst_moving, std::abs(e) / kt[j] * 1000.0);
        logged_sq[j] += (logged_friction[j] - curve) * (logged_friction[j] - curve);
        ++moving[static_cast<std::size_t>(j)];
      } else if (dq[j] == 0.0) {
        const double e = motor[j] - (tau[j] + logged_friction[j]);
        resting_sq[j] += e * e;
        ++resting[static_cast<std::size_t>(j)];
      }
    }
  }
  for (int j = 0; j < kArm9Joints; ++j) {
    const auto jj = static_cast<std::size_t>(j);
    ASSERT_GT(moving[jj], 300) << "joint " << j + 1 << " hardly moved";
    ASSERT_GT(resting[jj], 300) << "joint " << j + 1 << " never rested";
    const double rms_moving = std::sqrt(moving_sq[j] / static_cast<double>(moving[jj]));
    const double rms_resting = std::sqrt(resting_sq[j] / static_cast<double>(resting[jj]));
    const double rms_logged = std::sqrt(logged_sq[j] / static_cast<double>(moving[jj]));
    const double rms_torque = std::sqrt(torque_sq[j] / static_cast<double>(log.rows()));
    const double noise = kt[j] * std::sqrt(6.0 * 6.0 + 1.0 / 12.0) / 1000.0;
    EXPECT_LT(rms_moving, 1.3 * noise) << "joint " << j + 1 << " (RMS torque " << rms_torque << ")";
    EXPECT_LT(rms_resting, 1.3 * noise) << "joint " << j + 1;
    // The friction at the logged q̇ (quantised, the step's end) against the step's mean q̇.
    EXPECT_LT(rms_logged, 0.005) << "joint " << j + 1;
    EXPECT_GT(rms_torque, 10.0 * noise) << "joint " << j + 1 << ": too small to be checked";
  }
  EXPECT_LT(worst_moving, 40.0);  // mA: below 7 σ of the noise over 10⁵ samples
}

// Static contacts: the pushes' joint torques are J_padᵀ·F of the pads file, and the arm at rest
// holds gravity, friction and the push with its motor current.
TEST(NineJointTwin, PushesOnThePadsGiveTheirJacobianTorquesAndTheMotorsHoldThem) {
  Scenario s = load_scenario(arm9_file("arm9-excitation.json"));
  s.kind = Scenario::Kind::kStaticContacts;
  const Log log = simulate_to_log(s, 92, 40.0);

  const tpf::RobotDescription robot = tpf::load_robot_description(s.robot_file);
  const auto model = tpf::load_robot<double, Eigen::Dynamic>(s.robot_file);
  tpf::Data<double, Eigen::Dynamic> data(model);
  const std::vector<tpf::Pad> pads = tpf::load_pads(s.pads_file, model);
  ASSERT_EQ(static_cast<int>(pads.size()), kArm9Pads);
  ASSERT_EQ(log.pad_count(), kArm9Pads);

  long pushed = 0, held = 0;
  std::vector<bool> pad_seen(kArm9Pads, false);
  double worst_tau_ext = 0.0, hold_sq = 0.0;
  for (Eigen::Index k = 0; k < log.rows(); ++k) {
    const int pad = static_cast<int>(log.col("gt_contact")(k)) - 1;
    const TwinVector q = arm9_row(log, "q", k), dq = arm9_row(log, "dq", k);
    const TwinVector tau_ext = arm9_row(log, "gt_tau_ext", k);
    if (pad >= 0) {
      // The log's q is quantised (≈ 6e-6 rad): the Jacobian at it, to that resolution.
      const tpf::Pad& p = pads[static_cast<std::size_t>(pad)];
      tpf::forward_kinematics(model, data, q);
      const tpf::Vector3<double> centre = tpf::world_point(data, p.link, p.center);
      const auto jacobian = tpf::point_jacobian(model, data, p.link, centre);
      const tpf::Vector3<double> force(log.col("gt_fx")(k), log.col("gt_fy")(k),
                                       log.col("gt_fz")(k));
      const TwinVector expected = jacobian.topRows<3>().transpose() * force;
      worst_tau_ext = std::max(worst_tau_ext, (tau_ext - expected).cwiseAbs().maxCoeff() /
                                                  std::max(1.0, expected.norm()));
      pad_seen[static_cast<std::size_t>(pad)] = true;
      ++pushed;
    } else {
      EXPECT_TRUE(tau_ext.isZero(0.0)) << "row " << k;
    }
    if (!dq.isZero(0.0)) continue;
    const TwinVector g = tpf::compute_gravity(model, data, q);
    for (int j = 0; j < kArm9Joints; ++j) {
      const double kt = robot.drives[static_cast<std::size_t>(j)].torque_constant;
      const double e =
          log.col(indexed_name("i", j + 1))(k) -
          ((g[j] - tau_ext[j]) / kt * 1000.0 + log.col(indexed_name("gt_fric", j + 1))(k));
      hold_sq += e * e;
    }
    ++held;
  }
  EXPECT_GT(pushed, 2000);
  EXPECT_GT(held, 2000);
  EXPECT_LT(worst_tau_ext, 1e-4);
  EXPECT_GE(std::count(pad_seen.begin(), pad_seen.end(), true), 3);
  // mA: the current's noise (6 mA) and rounding.
  EXPECT_LT(std::sqrt(hold_sq / static_cast<double>(held * kArm9Joints)), 8.0);
}

}  // namespace
