// The state machine and the static-friction baseline on hand-made sequences.
#include "tpf/estimation/static_friction_tracker.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "support/constants.hpp"

namespace {

using tpf::test::kPeriod;
constexpr double kNone = std::numeric_limits<double>::infinity();
using Vec2 = tpf::JointVector<double, 2>;
using Tracker = tpf::StaticFrictionTracker<double, 2>;

const Vec2 kStill = Vec2::Zero();
const Vec2 kNoHeld = Vec2::Zero();

TEST(StaticFrictionTracker, FrozenBaselineIsTheResidualJustBeforeTheOnsetNotAtDetection) {
  Tracker tracker;
  const Vec2 c(120.0, -40.0);  // static friction the drives settled at (any torque unit)
  const double t_on = 1.0, t_detect = 1.05;
  // The push starts at t_on and grows 800 mA/s on joint 0 and −300 mA/s on joint 1; the pad
  // detects it only at t_detect.
  auto residual = [&](double t) {
    return t < t_on ? c : Vec2(c + (t - t_on) * Vec2(800.0, -300.0));
  };
  double t = 0;
  for (int k = 0; t < t_detect - 1e-9; ++k) {
    t = k * kPeriod;
    tracker.update(t, kStill, residual(t), false, kNone, kNoHeld);
    EXPECT_EQ(tracker.state(), tpf::ContactState::StaticFree);
  }
  // In state (i) the baseline follows τ_res (already contaminated just before detection).
  EXPECT_GT(tracker.friction_estimate()[0], c[0] + 20.0);
  t += kPeriod;
  tracker.update(t, kStill, residual(t), true, t_on, kNoHeld);
  EXPECT_EQ(tracker.state(), tpf::ContactState::StaticContact);
  EXPECT_NEAR(tracker.friction_estimate()[0], c[0], 1e-12);
  EXPECT_NEAR(tracker.friction_estimate()[1], c[1], 1e-12);
  EXPECT_EQ(tracker.onset_mask(), 3u);
  // While static with contact: τ̂_ext residual = τ_res − τ̂_fric,s = Δτ_res, model-free.
  for (int k = 0; k < 100; ++k) {
    t += kPeriod;
    tracker.update(t, kStill, residual(t), true, kNone, kNoHeld);
    EXPECT_NEAR(tracker.static_external()[0], (t - t_on) * 800.0, 1e-9);
    EXPECT_NEAR(tracker.static_external()[1], (t - t_on) * -300.0, 1e-9);
  }
}

TEST(StaticFrictionTracker, TransitionsWithSeveralPadsContactEndAndMotion) {
  Tracker tracker;
  double t = 0;
  auto step = [&](const Vec2& dq, const Vec2& r, bool contact, double onset = kNone,
                  const Vec2& held = kNoHeld) {
    t += kPeriod;
    tracker.update(t, dq, r, contact, onset, held);
  };
  for (int k = 0; k < 20; ++k)
    step(kStill, Vec2(10, 20), false);
  EXPECT_EQ(tracker.state(), tpf::ContactState::StaticFree);
  EXPECT_EQ(tracker.valid_mask(), 3u);
  step(kStill, Vec2(10, 20), true, t - 0.02);  // pad A on
  EXPECT_EQ(tracker.state(), tpf::ContactState::StaticContact);
  for (int k = 0; k < 10; ++k)
    step(kStill, Vec2(60, 0), true);
  step(kStill, Vec2(90, -30), true, t);  // pad B on as well: the first baseline stays
  EXPECT_EQ(tracker.friction_estimate(), Vec2(10, 20));
  EXPECT_EQ(tracker.static_external(), Vec2(80, -50));
  // Contact ends: back to (i), the baseline follows the residual again.
  for (int k = 0; k < 10; ++k)
    step(kStill, Vec2(15, 25), false);
  EXPECT_EQ(tracker.state(), tpf::ContactState::StaticFree);
  EXPECT_EQ(tracker.friction_estimate(), Vec2(15, 25));
  EXPECT_EQ(tracker.frozen_mask(), 0u);
  // Joint 0 moves: (iii); its τ̂_fric,s (the TCN input) is 0, joint 1 keeps its own.
  step(Vec2(0.05, 0.0), Vec2(400, 25), false);
  EXPECT_EQ(tracker.state(), tpf::ContactState::Dynamic);
  EXPECT_EQ(tracker.friction_estimate()[0], 0.0);
  EXPECT_EQ(tracker.friction_estimate()[1], 25.0);
  EXPECT_EQ(tracker.valid_mask(), 2u);
  EXPECT_FALSE(tracker.is_static(0));
  // Velocity just below the threshold counts as static.
  step(Vec2(0.9e-4, 0.0), Vec2(300, 25), false);
  EXPECT_EQ(tracker.state(), tpf::ContactState::StaticFree);
  EXPECT_EQ(tracker.friction_estimate()[0], 300.0);
}

TEST(StaticFrictionTracker, StoppingInContactHoldsTheLastEstimateOrKeepsTheStaleBaseline) {
  for (const auto policy : {tpf::StopPolicy::HoldLastEstimate, tpf::StopPolicy::KeepStale}) {
    tpf::StaticFrictionSettings<double> settings;
    settings.stop_policy = policy;
    Tracker tracker(settings);
    double t = 0;
    for (int k = 0; k < 20; ++k)
      tracker.update(t += kPeriod, kStill, Vec2(50, 5), false, kNone, kNoHeld);
    // Moves while a hand holds it, then stops with the hand still on.
    for (int k = 0; k < 20; ++k)
      tracker.update(t += kPeriod, Vec2(0.2, 0.1), Vec2(500, 300), true, kNone, kNoHeld);
    EXPECT_EQ(tracker.valid_mask(), 0u);
    const Vec2 held(-120, 40);  // the moving estimator's last external residual
    tracker.update(t += kPeriod, kStill, Vec2(480, 290), true, kNone, held);
    EXPECT_EQ(tracker.state(), tpf::ContactState::StaticContact);
    EXPECT_EQ(tracker.onset_mask(), 0u);
    if (policy == tpf::StopPolicy::HoldLastEstimate) {
      EXPECT_EQ(tracker.friction_estimate(), Vec2(600, 250));
      EXPECT_EQ(tracker.static_external(), held);
    } else {
      EXPECT_EQ(tracker.friction_estimate(), Vec2(50, 5));
    }
    // Held from there on: the estimate follows Δτ_res.
    tracker.update(t += kPeriod, kStill, Vec2(470, 300), true, kNone, Vec2(7, 7));
    if (policy == tpf::StopPolicy::HoldLastEstimate) {
      EXPECT_EQ(tracker.static_external(), Vec2(-130, 50));
    }
  }
}

}  // namespace
