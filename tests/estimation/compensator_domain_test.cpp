// Outside the compensator's domain (speed or acceleration) the fused estimate is the nominal one,
// for as long as the out-of-domain input stays in the network's window: a network that
// extrapolates badly at speeds it never saw cannot raise the torque-only contact alarm, and a
// push off the pads still can (hand-made samples on the twin's nominal model).
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tpf/common/error.hpp"
#include "tpf/estimation/compensator_weight_files.hpp"
#include "tpf/nn/tcn_weight_file.hpp"
#include "twin_fixture.hpp"

namespace {

using namespace tpf;
using namespace tpf::test;

/// A compensator that answers a constant b whatever its input: a network far outside its
/// training data (the demo's joint-1 network read −85 mA at 3 rad/s, trained up to 0.8 rad/s).
struct ConstantCompensator {
  using Output = Eigen::Matrix<double, kJoints, 1>;
  const Output& step(const CompensatorInput<double, kJoints>&) noexcept { return b; }
  void reset(const CompensatorInput<double, kJoints>&) noexcept {}
  Output b = Output::Zero();
};
using DomainEstimator = Estimator<double, kJoints, kPads, ConstantCompensator>;

/// The same with a memory: its output depends on its last kReceptiveField inputs, like a TCN's.
struct ConstantCompensatorWithMemory : ConstantCompensator {
  static constexpr int kReceptiveField = 8;
};
static_assert(compensator_memory<ConstantCompensator> == 1);
static_assert(compensator_memory<ConstantCompensatorWithMemory> == 8);
static_assert(compensator_memory<ZeroCompensator<double, kJoints>> == 1);

constexpr double kNominalSigma = 100.0, kFusedSigma = 20.0;  // N·m: bands 150 and 30
constexpr double kExtrapolation = 300.0;                     // N·m, the network's wrong answer
constexpr int kAlarmSamples = 10;

EstimatorParameters<double, kJoints> domain_parameters(double speed_limit) {
  auto p = twin_parameters();
  p.nominal_sigma.setConstant(kNominalSigma);
  p.fused_sigma.setConstant(kFusedSigma);
  p.torque_alarm_samples = kAlarmSamples;
  p.compensator_speed_limit.setConstant(speed_limit);
  return p;
}

/// 0.5 s of joint 1 turning at `speed` (the others at rest, no pad touched) with the effort the
/// nominal model predicts minus `push` N·m on joint 1 (an external torque +push off the pads),
/// so τ_res = −push exactly. q̈ = 0 is given.
std::vector<ArmSample> turning(double speed, double push) {
  const auto nominal = twin_nominal();
  Data<double, kJoints> data(nominal.model);
  std::vector<ArmSample> samples(200);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    ArmSample& s = samples[k];
    s.t = 0.0025 * double(k);
    s.q << -1.0 + speed * s.t, 0.3, 0.4, 0.1;
    s.dq << speed, 0.0, 0.0, 0.0;
    s.ddq.setZero();
    s.has_ddq = true;
    Vec rigid, friction;
    predict_effort(nominal, data, s.q, s.dq, s.ddq, rigid, friction);
    s.effort = rigid + friction;
    s.effort[0] -= push;
    s.pressure.setZero();
  }
  return samples;
}

struct DomainRun {
  int alarms = 0, first_alarm = -1, outside = 0;
  double last_fused = 0.0;  ///< joint 1's Fused external residual at the last sample (N·m)
};

DomainRun run(double speed, double push, double speed_limit) {
  ConstantCompensator c;
  c.b[0] = kExtrapolation;
  auto est = std::make_unique<DomainEstimator>(twin_nominal(), twin_pads(),
                                               domain_parameters(speed_limit), c);
  DomainRun r;
  const auto samples = turning(speed, push);
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const auto& out = est->update(samples[k]);
    if (out.contact && r.first_alarm < 0) r.first_alarm = int(k);
    r.alarms += out.contact ? 1 : 0;
    r.outside += (out.status & kStatusOutsideCompensatorDomain) ? 1 : 0;
    r.last_fused = out.estimate(TorqueEstimator::Fused).residual[0];
  }
  return r;
}

TEST(CompensatorDomain, WithoutALimitTheExtrapolatingNetworkRaisesAFalseAlarm) {
  const DomainRun r = run(2.0, 0.0, std::numeric_limits<double>::infinity());
  EXPECT_EQ(r.outside, 0);
  EXPECT_NEAR(r.last_fused, -(kExtrapolation - 1.5 * kFusedSigma), 1e-6);  // d(0 − b, 30)
  EXPECT_EQ(r.first_alarm, kAlarmSamples - 1);
}

TEST(CompensatorDomain, FasterThanTheDomainTheFusedEstimateIsTheNominalOne) {
  const DomainRun r = run(2.0, 0.0, 1.0);
  EXPECT_EQ(r.outside, 200);
  EXPECT_NEAR(r.last_fused, 0.0, 1e-6);  // d(τ_res = 0, 150), not d(0 − b, 30)
  EXPECT_EQ(r.alarms, 0);
}

TEST(CompensatorDomain, APushOffThePadsStillAlarmsOutsideTheDomain) {
  const double push = 400.0;  // N·m beyond the nominal band 150
  const DomainRun r = run(2.0, push, 1.0);
  EXPECT_NEAR(r.last_fused, -(push - 1.5 * kNominalSigma), 1e-6);
  EXPECT_EQ(r.first_alarm, kAlarmSamples - 1);
  EXPECT_EQ(r.alarms, 200 - (kAlarmSamples - 1));
}

TEST(CompensatorDomain, InsideTheDomainTheCompensatorIsUsed) {
  const DomainRun r = run(0.5, 0.0, 1.0);
  EXPECT_EQ(r.outside, 0);
  EXPECT_NEAR(r.last_fused, -(kExtrapolation - 1.5 * kFusedSigma), 1e-6);
}

// A hard stop (a joint limit, an impact) drives q̈ far beyond what the network was trained on:
// from that cycle the fused estimate of that joint is the nominal one, for the network's whole
// input window (8 cycles here), then the network is back; the other joints keep theirs.
TEST(CompensatorDomain, BeyondTheAccelerationDomainTheNominalEstimateHoldsForTheNetworksWindow) {
  ConstantCompensatorWithMemory c;
  c.b.setConstant(kExtrapolation);
  auto p = domain_parameters(1.0);
  p.compensator_acceleration_limit.setConstant(2.0);
  auto est = std::make_unique<Estimator<double, kJoints, kPads, ConstantCompensatorWithMemory>>(
      twin_nominal(), twin_pads(), p, c);
  auto samples = turning(0.5, 0.0);
  constexpr int kStop = 100;
  samples[kStop].ddq[0] = 10.0;  // given q̈ (the effort is not recomputed: only the domain counts)
  for (int k = 0; k < static_cast<int>(samples.size()); ++k) {
    const auto& out = est->update(samples[static_cast<std::size_t>(k)]);
    const bool outside = k >= kStop && k < kStop + 8;
    EXPECT_EQ(bool(out.status & kStatusOutsideCompensatorDomain), outside) << "cycle " << k;
    const auto& fused = out.estimate(TorqueEstimator::Fused).residual;
    if (k == kStop) {  // τ_res = −M·q̈ there: whatever it is, not the network's answer
      EXPECT_EQ(fused[0], dead_band(out.residual, Vec(Vec::Constant(1.5 * kNominalSigma)))[0]);
    } else if (outside) {  // d(τ_res = 0, 150): the nominal estimate, in the network's window
      EXPECT_EQ(fused[0], 0.0) << "cycle " << k;
    } else {
      EXPECT_NEAR(fused[0], -(kExtrapolation - 1.5 * kFusedSigma), 1e-6) << "cycle " << k;
    }
    if (k != kStop) {  // (at kStop joint 2's τ_res carries the coupling M₂₁·q̈₁)
      EXPECT_NEAR(fused[1], -(kExtrapolation - 1.5 * kFusedSigma), 1e-6) << "cycle " << k;
    }
  }
}

// The wrench weighs a joint outside the domain as the nominal estimate it falls back to: on a
// teaching log (a hand moves the arm by a pad), an estimator whose network answers nonsense
// (300 N·m) on every moving joint but whose domain ends at rest gives the same force and external
// torque as one with a silent network and σ_fused = σ_nominal — wherever no baseline was held at a
// stop (that σ stays the in-domain one: a joint stops through the domain).
TEST(CompensatorDomain, TheWrenchWeighsAJointOutsideTheDomainByTheNominalSigma) {
  const auto samples = samples_from_log(twin_log("teaching", 3, 6));
  ConstantCompensator nonsense, silent;
  nonsense.b.setConstant(kExtrapolation);
  auto outside = std::make_unique<DomainEstimator>(twin_nominal(), twin_pads(),
                                                   domain_parameters(0.0), nonsense);
  auto p = domain_parameters(std::numeric_limits<double>::infinity());
  p.fused_sigma = p.nominal_sigma;
  auto reference = std::make_unique<DomainEstimator>(twin_nominal(), twin_pads(), p, silent);
  int compared = 0;
  for (const ArmSample& s : samples) {
    const auto& a = outside->update(s);
    const auto& b = reference->update(s);
    const auto held = [](const DomainEstimator& e) {
      return e.tracker().frozen_mask() & ~e.tracker().onset_mask();
    };
    if (a.wrench.pad < 0 || held(*outside) || held(*reference)) continue;
    ASSERT_EQ(a.wrench.pad, b.wrench.pad);
    ASSERT_TRUE((a.status & kStatusOutsideCompensatorDomain) || a.state != ContactState::Dynamic);
    EXPECT_LT((a.wrench.force_world - b.wrench.force_world).norm(), 1e-9);
    EXPECT_LT((a.external.torque - b.external.torque).norm(), 1e-9);
    ++compared;
  }
  EXPECT_GT(compared, 200);
}

}  // namespace

// The held-out gate: a joint whose network is gated off runs on the nominal residual and band,
// flagged every cycle, whatever the network answers; the other joints keep theirs.
TEST(CompensatorGate, AGatedJointRunsOnTheNominalResidual) {
  ConstantCompensator c;
  c.b.setConstant(kExtrapolation);
  auto est =
      std::make_unique<DomainEstimator>(twin_nominal(), twin_pads(), domain_parameters(1.0), c);
  est->set_compensated_joints(~1u);  // joint 1 gated off
  EXPECT_EQ(est->compensated_joints(), 0b1110u);
  int gated = 0, alarms = 0;
  for (const ArmSample& s : turning(0.5, 0.0)) {
    const auto& out = est->update(s);
    gated += (out.status & kStatusCompensatorGated) ? 1 : 0;
    alarms += out.contact ? 1 : 0;
    EXPECT_EQ(out.estimate(TorqueEstimator::Fused).residual[0], 0.0);  // d(τ_res = 0, 150)
    EXPECT_NEAR(out.estimate(TorqueEstimator::Fused).residual[1],
                -(kExtrapolation - 1.5 * kFusedSigma), 1e-6);  // the network's, d(0 − b, 30)
  }
  EXPECT_EQ(gated, 200);
  EXPECT_LE(alarms, 200 - (kAlarmSamples - 1));  // joints 2–4 still alarm on their network
}

// The gate reads the held-out gains the weight files hold: a joint's network is kept when its
// gain reaches the threshold in every regime scored, gated off otherwise, and a file without a
// score keeps its network; a bad held_out field is refused naming file and field.
TEST(CompensatorGate, ReadsTheHeldOutGainsOfTheWeightFiles) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("tpf-gate-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path shipped = fs::path(TPF_TEST_DATA_DIR) / "weights" / "arm4.tcn.json";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::array<double, 3>> gains{
      {0.9, 0.7, 0.3}, {0.9, 0.7, -0.08}, {nan, 0.4, 0.1}, {0.0, 0.0, 0.0}};
  for (int j = 0; j < kJoints; ++j) {
    TcnWeightFile f = read_tcn_weight_file(joint_weight_path(shipped, j).string());
    if (j < 3)
      for (int r = 0; r < 3; ++r)
        f.held_out_gain[static_cast<std::size_t>(r)] = {
            gains[static_cast<std::size_t>(j)][static_cast<std::size_t>(r)]};
    write_tcn_weight_file(joint_weight_path(dir / "arm4.tcn.json", j).string(), f);
  }
  const CompensatorWeightFiles w = find_compensator_weights(dir / "arm4.tcn.json", kJoints);
  std::vector<std::string> gated;
  EXPECT_EQ(compensated_joints(w, kJoints, 0.0, &gated), 0b1101u);  // joint 2 worse when moving
  ASSERT_EQ(gated.size(), 1u);
  EXPECT_EQ(gated[0], "joint 2: held-out gain -8.0 % at moving < +0.0 %");
  EXPECT_EQ(compensated_joints(w, kJoints, 0.2), 0b1001u);  // joint 3 below, 4 not scored
  EXPECT_EQ(read_tcn_weight_file(w.files[2]).held_out_gain[0].size(), 1u);
  EXPECT_TRUE(std::isnan(read_tcn_weight_file(w.files[2]).held_out_gain[0][0]));  // null

  // A bad field, named.
  nlohmann::json j = nlohmann::json::parse(std::ifstream(w.files[0]));
  j["held_out"]["moving"] = {0.1, 0.2};
  std::ofstream(dir / "bad.json") << j.dump();
  try {
    read_tcn_weight_file((dir / "bad.json").string());
    ADD_FAILURE() << "a held_out of two outputs for one was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json: held_out.moving: must be an array of 1"),
              std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}
