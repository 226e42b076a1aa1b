// LuGre friction: steady state equals Stribeck, pre-sliding spring, hysteresis at reversal,
// unconditional stability of the exponential bristle update, stick–slip, no allocation.
#include "tpf/friction/lugre.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/allocation_counter.hpp"

namespace {

using Vec = tpf::JointVector<double, 4>;

tpf::LuGreParameters<double, 4> lugre_reference() {
  tpf::LuGreParameters<double, 4> p;
  p.stribeck.coulomb << 1.3, 1.6, 0.9, 0.6;
  p.stribeck.static_friction << 2.1, 2.5, 1.45, 1.0;
  p.stribeck.stribeck_velocity << 0.04, 0.035, 0.05, 0.06;
  p.stribeck.stribeck_exponent << 1.5, 1.5, 1.2, 2.0;
  p.stribeck.viscous << 2.6, 3.2, 1.6, 1.1;
  p.stribeck.load_coulomb << 0.0, 0.045, 0.06, 0.08;
  p.stribeck.load_viscous << 0.0, 0.06, 0.08, 0.1;
  p.bristle_stiffness << 1.2e4, 1.4e4, 8e3, 6e3;
  p.bristle_damping << 40, 50, 25, 15;
  return p;
}

TEST(LuGre, SteadyStateEqualsStribeck) {
  const auto p = lugre_reference();
  const Vec ag(0.0, 9.0, 4.0, 1.5);
  for (double v : {-1.2, -0.05, -0.004, 0.001, 0.02, 0.3, 2.0}) {
    tpf::LuGreState<double, 4> state;
    const Vec dq = Vec::Constant(v);
    Vec tau = Vec::Zero();
    // Slide for 0.05 rad (far beyond the pre-sliding range) at 2 kHz.
    const double dt = 5e-4;
    const int steps = static_cast<int>(std::ceil(0.05 / (std::abs(v) * dt)));
    for (int k = 0; k < steps; ++k)
      tau = tpf::lugre_step(p, state, dq, ag, dt);
    const Vec expected = tpf::stribeck_friction(p.stribeck, dq, ag);
    EXPECT_LT((tau - expected).cwiseAbs().maxCoeff(), 1e-9 * (1 + expected.cwiseAbs().maxCoeff()))
        << "v = " << v;
    EXPECT_TRUE(state.z.isApprox(tpf::lugre_steady_deflection(p, dq, ag)));
  }
}

TEST(LuGre, PreSlidingIsASpringOfStiffnessSigma0) {
  const auto p = lugre_reference();
  tpf::LuGreState<double, 4> state;
  const double dt = 5e-4, v = 1e-4;  // displacement 1e-6 rad per 20 steps, far below τ_s/σ0
  Vec tau = Vec::Zero();
  for (int k = 0; k < 20; ++k)
    tau = tpf::lugre_step(p, state, Vec(Vec::Constant(v)), Vec(Vec::Zero()), dt);
  const double x = 20 * v * dt;
  for (int j = 0; j < 4; ++j) {
    const double spring =
        p.bristle_stiffness[j] * x + p.bristle_damping[j] * v + p.stribeck.viscous[j] * v;
    // The bristle equation departs from a pure spring by O(σ0·x/g) ≈ 0.6 % at this displacement.
    EXPECT_NEAR(tau[j], spring, 1e-2 * spring) << "joint " << j;
    EXPECT_LT(tau[j], spring);
  }
}

TEST(LuGre, ReversalShowsHysteresis) {
  // Slide forward to steady state, then reverse: the friction does not jump to −g but passes
  // through zero after a pre-sliding displacement of about g(0)/σ0 (Dahl-like memory).
  const auto p = lugre_reference();
  tpf::LuGreState<double, 4> state;
  const double dt = 5e-4, v = 0.002;
  for (int k = 0; k < 4000; ++k)
    tpf::lugre_step(p, state, Vec(Vec::Constant(v)), Vec(Vec::Zero()), dt);
  const Vec forward = tpf::lugre_step(p, state, Vec(Vec::Constant(v)), Vec(Vec::Zero()), dt);
  const Vec first_back = tpf::lugre_step(p, state, Vec(Vec::Constant(-v)), Vec(Vec::Zero()), dt);
  for (int j = 0; j < 4; ++j) {
    EXPECT_GT(forward[j], 0.9 * p.stribeck.static_friction[j] - 1e-9);
    EXPECT_GT(first_back[j], 0.5 * forward[j]) << "friction must not flip at once";
  }
  // Displacement needed to cross zero, per joint, compared with z_ss = g/σ0.
  Vec crossed = Vec::Constant(-1);
  for (int k = 1; k < 4000; ++k) {
    const Vec tau = tpf::lugre_step(p, state, Vec(Vec::Constant(-v)), Vec(Vec::Zero()), dt);
    for (int j = 0; j < 4; ++j)
      if (crossed[j] < 0 && tau[j] < 0) crossed[j] = (k + 1) * v * dt;
  }
  for (int j = 0; j < 4; ++j) {
    const double z_ss = tpf::stribeck_level(p.stribeck, j, v, 0.0) / p.bristle_stiffness[j];
    EXPECT_GT(crossed[j], 0.3 * z_ss);
    EXPECT_LT(crossed[j], 1.5 * z_ss);
  }
}

TEST(LuGre, ExponentialUpdateIsStableForHugeSteps) {
  const auto p = lugre_reference();
  for (double dt : {1e-3, 1e-1, 10.0}) {
    for (double v : {-3.0, -0.1, 0.5, 3.0}) {
      const double z0 = 5e-4;
      const auto step = tpf::lugre_joint_step(p, 0, z0, v, 0.0, dt);
      const double z_ss = tpf::stribeck_level(p.stribeck, 0, v, 0.0) / p.bristle_stiffness[0];
      EXPECT_LE(std::abs(step.z), std::max(std::abs(z0), z_ss) + 1e-15);
      // It moves monotonically from z0 towards the steady deflection.
      const double target = v > 0 ? z_ss : -z_ss;
      EXPECT_LE(std::abs(step.z - target), std::abs(z0 - target) + 1e-15);
    }
  }
}

TEST(LuGre, DrivenMassShowsStickSlip) {
  // Classic test rig: unit inertia pulled through a spring whose far end moves at 5 mrad/s.
  tpf::LuGreParameters<double, 1> p;
  p.stribeck.coulomb << 1.0;
  p.stribeck.static_friction << 1.5;
  p.stribeck.stribeck_velocity << 0.01;
  p.stribeck.stribeck_exponent << 2.0;
  p.stribeck.viscous << 0.0;
  p.bristle_stiffness << 1e4;
  p.bristle_damping << 20.0;
  tpf::LuGreState<double, 1> state;
  const double k = 20.0, v_drive = 0.005, dt = 2e-5;
  double x = 0, v = 0;
  int stick_to_slip = 0;
  bool slipping = false;
  for (int n = 0; n < static_cast<int>(30.0 / dt); ++n) {
    const double t = n * dt;
    const tpf::JointVector<double, 1> vel(v);
    const double f = tpf::lugre_step(p, state, vel, tpf::JointVector<double, 1>(0.0), dt)[0];
    v += dt * (k * (v_drive * t - x) - f);
    x += dt * v;
    if (!slipping && v > 4 * v_drive) {
      slipping = true;
      ++stick_to_slip;
    } else if (slipping && std::abs(v) < 0.2 * v_drive) {
      slipping = false;
    }
  }
  // Each cycle the spring must gain (τ_s − τ_c-ish) to break away: ≈ 2·0.5/(k·v_drive) = 10 s.
  EXPECT_GE(stick_to_slip, 2);
  EXPECT_LE(stick_to_slip, 10);
}

TEST(LuGre, StepAllocatesNothing) {
  const auto p = lugre_reference();
  tpf::LuGreState<double, 4> state;
  const Vec dq(0.3, -0.2, 0.0, -0.05), ag(0.0, 7.0, 3.0, 1.0);
  Vec sum = Vec::Zero();
  tpf::test::AllocationCounter counter;
  for (int k = 0; k < 100; ++k)
    sum += tpf::lugre_step(p, state, dq, ag, 5e-4);
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(sum.allFinite());
}

}  // namespace
