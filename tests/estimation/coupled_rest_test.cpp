// Rest per motor with a coupled transmission: a joint is at rest only when every motor acting on
// it is (|(C·q̇)_m| < static_velocity for each m with C(m, j) ≠ 0). A still joint that a turning
// motor acts on feels that motor's kinetic friction, so no baseline is held on it and its external
// torque is the moving estimate. Hand-made tracker sequences with planar2_coupled's C, the
// identity coupling giving the per-joint tracker bit for bit on a twin log, and the twin's arm
// with a coupled wrist pair (simulated): a push estimated while the coupled motor reverses, the
// estimator of fixed and run-time joint count (loaded from files, as the offline tools do)
// agreeing without a heap allocation per cycle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "support/allocation_counter.hpp"
#include "support/constants.hpp"
#include "support/temp_dir.hpp"
#include "tpf/estimation/load_estimator.hpp"
#include "tpf/estimation/static_friction_tracker.hpp"
#include "twin_fixture.hpp"

namespace tpf::test {
namespace {

constexpr double kNoOnset = std::numeric_limits<double>::infinity();

// --- The tracker alone, planar2_coupled's transmission ----------------------------------------

using PlanarVec = JointVector<double, 2>;
using Tracker2 = StaticFrictionTracker<double, 2>;

/// tests/generator/planar2/planar2_coupled.robot.json: motor 2 turns with q2 + 0.5·q1, so it acts
/// on joint 1 (C(1, 0) = 0.5) and joint 2; motor 1 on joint 1 alone.
Eigen::Matrix2d planar2_coupling() {
  Eigen::Matrix2d c;
  c << 1.0, 0.0, 0.5, 1.0;
  return c;
}

TEST(CoupledRest, AStillJointThatATurningMotorActsOnIsNotAtRest) {
  Tracker2 coupled, per_joint;
  coupled.set_coupling(planar2_coupling());
  ASSERT_TRUE(coupled.coupled());
  ASSERT_FALSE(per_joint.coupled());
  double t = 0;
  const PlanarVec zero = PlanarVec::Zero();
  auto step = [&](const PlanarVec& dq, const PlanarVec& r, bool contact = false,
                  double onset = kNoOnset) {
    t += kPeriod;
    coupled.update(t, dq, r, contact, onset, zero);
    per_joint.update(t, dq, r, contact, onset, zero);
  };
  // Both still: both motors at rest, a baseline on both joints, as without coupling.
  for (int k = 0; k < 20; ++k)
    step(zero, PlanarVec(3.0, -2.0));
  EXPECT_EQ(coupled.valid_mask(), 3u);
  EXPECT_EQ(coupled.state(), ContactState::StaticFree);
  EXPECT_EQ(coupled.friction_estimate(), PlanarVec(3.0, -2.0));
  // Joint 1 still, joint 2 turning: motor 2 (q2 + 0.5·q1) turns and acts on joint 1 → joint 1 is
  // not at rest (no baseline, τ̂_fric,s = 0); per joint it would keep its baseline.
  step(PlanarVec(0.0, 0.2), PlanarVec(3.0, 9.0));
  EXPECT_EQ(coupled.valid_mask(), 0u);
  EXPECT_FALSE(coupled.is_static(0));
  EXPECT_FALSE(coupled.is_static(1));
  EXPECT_EQ(coupled.friction_estimate(), zero);
  EXPECT_EQ(coupled.static_external(), zero);
  EXPECT_EQ(per_joint.valid_mask(), 1u);
  EXPECT_EQ(per_joint.friction_estimate()[0], 3.0);
  // Motor 2 just below the threshold: |0.5·0 + 0.9e-4| < 1e-4 → both at rest again.
  step(PlanarVec(0.0, 0.9e-4), PlanarVec(5.0, 1.0));
  EXPECT_EQ(coupled.valid_mask(), 3u);
  EXPECT_EQ(coupled.friction_estimate(), PlanarVec(5.0, 1.0));  // a new static stretch: this sample
  // Joint 1 turning at 0.2, joint 2 at −0.1: motor 2 = −0.1 + 0.5·0.2 = 0 stands still and is the
  // only motor on joint 2, but joint 2 turns (its dynamics are not at rest): no joint at rest.
  step(PlanarVec(0.2, -0.1), PlanarVec(6.0, 7.0));
  EXPECT_EQ(coupled.valid_mask(), 0u);
  EXPECT_EQ(coupled.friction_estimate(), zero);
  EXPECT_EQ(per_joint.valid_mask(), 0u);
  EXPECT_EQ(coupled.state(), ContactState::Dynamic);
}

TEST(CoupledRest, ABaselineFrozenAtOnsetIsDroppedWhenACoupledMotorStartsAndHeldAgainAtItsStop) {
  Tracker2 coupled, per_joint;
  coupled.set_coupling(planar2_coupling());
  double t = 0;
  const PlanarVec zero = PlanarVec::Zero();
  auto step = [&](const PlanarVec& dq, const PlanarVec& r, bool contact, double onset = kNoOnset,
                  const PlanarVec& held = PlanarVec::Zero()) {
    t += kPeriod;
    coupled.update(t, dq, r, contact, onset, held);
    per_joint.update(t, dq, r, contact, onset, held);
  };
  for (int k = 0; k < 20; ++k)
    step(zero, PlanarVec(3.0, -2.0), false);
  step(zero, PlanarVec(3.0, -2.0), true, t - 0.01);  // a pad on: both baselines frozen
  EXPECT_EQ(coupled.frozen_mask(), 3u);
  EXPECT_EQ(coupled.onset_mask(), 3u);
  EXPECT_EQ(coupled.state(), ContactState::StaticContact);
  step(zero, PlanarVec(1.0, -2.0), true);  // a push of 2 on joint 1
  EXPECT_EQ(coupled.static_external(), PlanarVec(-2.0, 0.0));
  // Joint 2 starts turning in contact, joint 1 stays still: motor 2's friction on joint 1 turns
  // kinetic (here +0.7 on joint 1), which joint 1's frozen baseline would read as a push.
  for (int k = 0; k < 10; ++k)
    step(PlanarVec(0.0, 0.3), PlanarVec(1.7, 4.0), true);
  EXPECT_EQ(coupled.valid_mask(), 0u);
  EXPECT_EQ(coupled.frozen_mask(), 0u);
  EXPECT_EQ(coupled.static_external(), zero);
  EXPECT_EQ(per_joint.valid_mask(), 1u);
  EXPECT_EQ(per_joint.frozen_mask(), 1u);
  EXPECT_NEAR(per_joint.static_external()[0], -1.3, 1e-12);  // the push of 2 read as 1.3
  // Joint 2 stops with the pad on: both joints stopped in contact (HoldLastEstimate), the
  // baseline is the residual less the moving estimate held at the stop.
  step(zero, PlanarVec(1.0, -2.0), true, kNoOnset, PlanarVec(-2.0, 0.5));
  EXPECT_EQ(coupled.valid_mask(), 3u);
  EXPECT_EQ(coupled.frozen_mask(), 3u);
  EXPECT_EQ(coupled.onset_mask(), 0u);
  EXPECT_EQ(coupled.friction_estimate(), PlanarVec(3.0, -2.5));
  EXPECT_EQ(coupled.static_external(), PlanarVec(-2.0, 0.5));
  EXPECT_EQ(coupled.state(), ContactState::StaticContact);
}

// The identity coupling gives the per-joint tracker's masks and outputs bit for bit, on the
// residuals, contacts and onsets of the twin's static-contacts log (pushes, stops in contact,
// motion of single joints).
TEST(CoupledRest, TheIdentityCouplingIsThePerJointTrackerBitForBit) {
  auto est = std::make_unique<TwinEstimator>(twin_nominal(), twin_pads(), twin_parameters());
  ASSERT_FALSE(est->tracker().coupled());
  StaticFrictionTracker<double, kJoints> identity(twin_parameters().static_friction),
      per_joint(twin_parameters().static_friction);
  identity.set_coupling(JointMatrix<double, kJoints>::Identity());
  std::size_t held = 0, moving = 0;
  for (const ArmSample& s : static_contact_samples()) {
    const Vec previous = est->output().external.residual;
    const auto& out = est->update(s);
    if (out.status & (kStatusNonFiniteInput | kStatusStaleTime)) continue;
    const bool contact = est->skin().any_contact();
    const double onset = est->skin().earliest_new_onset();
    identity.update(s.t, s.dq, out.residual, contact, onset, previous);
    per_joint.update(s.t, s.dq, out.residual, contact, onset, previous);
    ASSERT_EQ(identity.valid_mask(), per_joint.valid_mask());
    ASSERT_EQ(identity.frozen_mask(), per_joint.frozen_mask());
    ASSERT_EQ(identity.onset_mask(), per_joint.onset_mask());
    ASSERT_EQ(identity.state(), per_joint.state());
    ASSERT_EQ(identity.friction_estimate(), per_joint.friction_estimate());
    ASSERT_EQ(identity.static_external(), per_joint.static_external());
    // … and the estimator's own tracker (uncoupled: the per-joint path, as before).
    ASSERT_EQ(est->tracker().valid_mask(), per_joint.valid_mask());
    held += per_joint.frozen_mask() != 0 ? 1 : 0;
    moving += per_joint.state() == ContactState::Dynamic ? 1 : 0;
  }
  EXPECT_GT(held, 100u);
  EXPECT_GT(moving, 100u);
}

// --- The estimator on the twin's arm with a coupled pair --------------------------------------

/// The twin's arm with motor 4 turning with q4 + 0.5·q3 (so it acts on joint 3 with 0.5).
JointMatrix<double, kJoints> wrist_coupling() {
  JointMatrix<double, kJoints> c = JointMatrix<double, kJoints>::Identity();
  c(3, 2) = 0.5;
  return c;
}

NominalModel<double, kJoints> coupled_twin_nominal() {
  NominalModel<double, kJoints> nominal = twin_nominal();
  nominal.model.set_coupling(wrist_coupling());
  return nominal;
}

/// Motor 4's kinetic friction the nominal model misses, ε·sgn((C·q̇)_4) [N·m] at the motor: on
/// joint 3 through C(3, 2) = 0.5, on joint 4 fully.
constexpr double kMissedCoulomb = 3.0;
Vec missed_friction(const Vec& dq) {
  const double rate = wrist_coupling().row(3).dot(dq);
  const double f = rate > 0 ? kMissedCoulomb : rate < 0 ? -kMissedCoulomb : 0.0;
  return wrist_coupling().transpose() * Vec(0.0, 0.0, 0.0, f);
}

/// A compensator that has learnt exactly that miss (from q̇ in its input): what a trained network
/// would give on the moving joints.
struct MissCompensator {
  using Output = Eigen::Matrix<double, kJoints, 1>;
  const Output& step(const CompensatorInput<double, kJoints>& x) noexcept {
    b = missed_friction(x.segment<kJoints>(kJoints));
    return b;
  }
  void reset(const CompensatorInput<double, kJoints>&) noexcept {}
  Output b = Output::Zero();
};

constexpr double kPush = 5.0;  ///< N·m on joint 3, an external torque (τ_res −5)
constexpr int kForearmTop = 4;
/// Phases [s]: all still; joint 4 turns at +ω; a pad on and the push (t_on); joint 4 reverses;
/// joint 4 stops (pad still on); end. Joints 1–3 never move.
constexpr double kTurnStart = 0.3, kPushOnset = 0.6, kReversal = 0.8, kTurnStop = 1.0,
                 kRunEnd = 1.2;
constexpr double kOmega = 0.4;

/// The samples: the nominal model's effort (rigid body and motor friction through Cᵀ), plus the
/// missed kinetic friction, minus the push; q̈ = 0 given. The pad reads 10 kPa from t_on (live:
/// it varies by 0.01 kPa steps, a constant reading would be a stuck pad).
std::vector<ArmSample> coupled_push_samples() {
  const auto nominal = coupled_twin_nominal();
  Data<double, kJoints> data(nominal.model);
  std::vector<ArmSample> samples;
  double q4 = 0.1;
  for (int k = 0; kPeriod * k < kRunEnd; ++k) {
    ArmSample s;
    s.t = kPeriod * k;
    const double w = s.t < kTurnStart  ? 0.0
                     : s.t < kReversal ? kOmega
                     : s.t < kTurnStop ? -kOmega
                                       : 0.0;
    s.q << 0.2, 0.5, 0.4, q4;
    s.dq << 0.0, 0.0, 0.0, w;
    q4 += w * kPeriod;
    s.ddq.setZero();
    s.has_ddq = true;
    Vec rigid, friction;
    predict_effort(nominal, data, s.q, s.dq, s.ddq, rigid, friction);
    s.effort = rigid + friction + missed_friction(s.dq);
    s.pressure.setZero();
    if (s.t >= kPushOnset) {
      s.effort[2] -= kPush;
      s.pressure[kForearmTop] = 10.0 + 0.01 * (k % 3);
    }
    samples.push_back(s);
  }
  return samples;
}

EstimatorParameters<double, kJoints> sharp_parameters() {
  EstimatorParameters<double, kJoints> p = twin_parameters();
  p.fused_sigma.setConstant(1e-3);  // the compensator is exact here: a 1.5e-3 N·m band
  p.nominal_sigma.setConstant(1e-3);
  return p;
}

// Joint 3 stands still while motor 4 (q4 + 0.5·q3) turns and then reverses, with a push of 5 N·m
// on joint 3 from t_on. Per joint, joint 3 would be at rest: its baseline frozen at t_on holds
// motor 4's kinetic friction at +ω, so after the reversal its static estimate reads the missed
// friction's change (2 · 0.5 · 3 = 3 N·m) as a push. Per motor, joint 3 is not at rest while
// motor 4 turns: the moving (fused) estimate serves it and is right, and when motor 4 stops in
// contact both joints hold that estimate.
TEST(CoupledRest, APushWhileTheCoupledMotorReversesIsNotReadAsTheFrictionChange) {
  using CoupledEstimator = Estimator<double, kJoints, kPads, MissCompensator>;
  auto est =
      std::make_unique<CoupledEstimator>(coupled_twin_nominal(), twin_pads(), sharp_parameters());
  ASSERT_TRUE(est->tracker().coupled());
  const auto p = sharp_parameters();
  StaticFrictionTracker<double, kJoints> per_joint(p.static_friction);  // the rule before
  const std::uint32_t joint3 = 1u << 2, wrist = joint3 | (1u << 3);
  double worst_per_motor = 0, worst_after_stop = 0, worst_per_joint_before = 0,
         worst_per_joint_after = 0;
  int contact_rows = 0;
  for (const ArmSample& s : coupled_push_samples()) {
    const auto& out = est->update(s);
    ASSERT_EQ(out.status & (kStatusNonFiniteInput | kStatusStaleTime), 0u);
    per_joint.update(s.t, s.dq, out.residual, est->skin().any_contact(),
                     est->skin().earliest_new_onset(), Vec::Zero());
    const auto& fixed = out.estimate(TorqueEstimator::StaticModelFree);
    const auto& fused = out.estimate(TorqueEstimator::Fused);
    const bool turning = s.t >= kTurnStart && s.t < kTurnStop;
    // Rest per motor: joint 3 is not at rest while motor 4 turns, joints 1 and 2 always are.
    EXPECT_EQ(fixed.valid, turning ? 0b0011u : 0b1111u) << "t " << s.t;
    EXPECT_EQ(est->tracker().valid_mask(), fixed.valid);
    EXPECT_EQ(out.state, turning                     ? ContactState::Dynamic
                         : est->skin().any_contact() ? ContactState::StaticContact
                                                     : ContactState::StaticFree)
        << "t " << s.t;
    EXPECT_EQ(per_joint.valid_mask() & joint3, joint3) << "t " << s.t;  // per joint: always
    // The TCN's input τ̂_fric,s: no held friction on joint 3 while motor 4 turns.
    EXPECT_EQ(out.static_friction[2], turning ? 0.0 : est->tracker().friction_estimate()[2]);
    if (!est->skin().any_contact() || s.t < kPushOnset + 0.05) continue;
    ++contact_rows;
    // Joint 3's torque-only estimate (StaticModelFree where valid, else Fused): truth −5.
    const double per_motor = (fixed.valid & joint3) ? fixed.residual[2] : fused.residual[2];
    double& worst_motor = turning ? worst_per_motor : worst_after_stop;
    worst_motor = std::max(worst_motor, std::abs(per_motor + kPush));
    if (turning) {
      const double e =
          std::abs(dead_band(per_joint.static_external()[2], p.static_dead_band[2]) + kPush);
      double& worst = s.t < kReversal ? worst_per_joint_before : worst_per_joint_after;
      worst = std::max(worst, e);
    } else {  // motor 4 stopped in contact: both held (from the fused estimate), the push kept
      EXPECT_EQ(est->tracker().frozen_mask() & wrist, wrist);
      EXPECT_EQ(est->tracker().onset_mask() & wrist, 0u);
    }
  }
  EXPECT_GT(contact_rows, 200);
  // Per motor: the push to within the fused band (1.5e-3 N·m) through the reversal; after the
  // stop the held estimate, within the static band (≈ 0.09 N·m) more.
  EXPECT_NEAR(worst_per_motor, 1.5e-3, 1e-9);
  EXPECT_NEAR(worst_after_stop, 1.5e-3 + p.static_dead_band[2], 1e-9);
  // Per joint: the push to within its static band until the reversal, then off by the change
  // of motor 4's missed kinetic friction on joint 3, 2·0.5·ε = 3 N·m (less the band).
  EXPECT_NEAR(worst_per_joint_before, p.static_dead_band[2], 1e-9);
  EXPECT_NEAR(worst_per_joint_after, kMissedCoulomb - p.static_dead_band[2], 1e-9);
}

// --- Fixed and run-time joint count, from files as the offline tools load them ----------------

/// data/arm4.robot.json with "coupled_to": {"joint3": 0.5} on joint 4, written into `dir`.
std::string coupled_arm4_robot_file(const TempDir& dir) {
  std::ifstream in(data_path("arm4.robot.json"));
  nlohmann::json robot = nlohmann::json::parse(in);
  robot["urdf"] = data_path("arm4.urdf");
  robot.erase("pads");
  robot.erase("friction");
  robot["joints"][3]["coupled_to"] = {{"joint3", 0.5}};
  const std::string path = (dir / "arm4_coupled.robot.json").string();
  std::ofstream(path) << robot.dump(2);
  return path;
}

// The shipped arm4 files with a coupled robot file, loaded as a controller (4 joints, 11 pads)
// and as the offline replay does (load_estimator at Eigen::Dynamic, what training and evaluation
// traces come from): both apply the rule per motor, agree, and allocate nothing per cycle.
TEST(CoupledRest, FixedAndRunTimeJointCountsAgreeAndAllocateNothing) {
  const TempDir dir("coupled_rest");
  EstimatorFiles files;
  files.params = data_path("arm4.params.json");
  files.robot = coupled_arm4_robot_file(dir);
  files.pads = data_path("arm4.pads.json");
  files.estimator = data_path("arm4.estimator.json");
  const auto fixed = load_estimator<kJoints, kPads>(files);
  const auto any = load_estimator<Eigen::Dynamic, Eigen::Dynamic>(files);
  ASSERT_TRUE(fixed->nominal().model.coupled);
  ASSERT_TRUE(fixed->tracker().coupled());
  ASSERT_TRUE(any->tracker().coupled());
  const std::vector<ArmSample> samples = coupled_push_samples();
  std::vector<EstimatorSample<double, Eigen::Dynamic, Eigen::Dynamic>> any_samples;
  for (const ArmSample& s : samples)
    any_samples.push_back(any_count_sample<Eigen::Dynamic>(s));
  std::size_t fixed_allocations = 0, any_allocations = 0;
  int joint3_not_at_rest = 0;
  for (std::size_t r = 0; r < samples.size(); ++r) {
    const std::size_t before = heap_allocation_count();
    const auto& f = fixed->update(samples[r]);
    const std::size_t between = heap_allocation_count();
    const auto& a = any->update(any_samples[r]);
    any_allocations += heap_allocation_count() - between;
    fixed_allocations += between - before;
    ASSERT_EQ(f.state, a.state) << "row " << r;
    for (int e = 0; e < kTorqueEstimatorCount; ++e) {
      ASSERT_EQ(f.estimates[e].valid, a.estimates[e].valid) << "row " << r;
      for (int j = 0; j < kJoints; ++j)
        ASSERT_NEAR(f.estimates[e].residual[j], a.estimates[e].residual[j], 1e-9) << "row " << r;
    }
    ASSERT_EQ(fixed->tracker().frozen_mask(), any->tracker().frozen_mask()) << "row " << r;
    const bool turning = samples[r].dq[3] != 0.0;
    EXPECT_EQ(bool(f.estimate(TorqueEstimator::StaticModelFree).valid & 0b0100u), !turning);
    joint3_not_at_rest += turning ? 1 : 0;
  }
  EXPECT_GT(joint3_not_at_rest, 200);
  EXPECT_EQ(fixed_allocations, 0u);
  EXPECT_EQ(any_allocations, 0u);
}

}  // namespace
}  // namespace tpf::test
