// Coupled transmissions on data the twin did not make: the generator's planar arm with motor 2
// turning with q₂ + 0.5·q₁ (planar2_coupled.robot.json, coupled_to joint1: with c = 1 motor 2's
// armature would only enter as D + I_a2, not identifiable apart from the forearm's inertia).
// identify recovers motor 2's Coulomb, viscous and armature and joint 1's friction within 5 %
// (joint 1's on a log without friction memory, see below); its held-out moving error
// per joint is at most 1.2× that of plain least squares of the generator's own model class (the
// closed-form planar dynamics with the coupling, fitted here with Eigen); the same log fitted
// without the coupling (planar2.robot.json) is clearly worse on joint 2. The nominal model
// evaluates each motor's curve on (C·q̇)_m through Cᵀ, bit for bit as before without coupling,
// and its file keeps the coupled model.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <cstdio>
#include <vector>

#include "offline/identify/identify.hpp"
#include "planar_arm_generator.hpp"
#include "support/heldout_moving_rms.hpp"
#include "support/temp_dir.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/friction/stribeck.hpp"
#include "tpf/model/load_robot.hpp"

namespace tpf::test {
namespace {

using offline::DataX;
using offline::Regime;
using offline::StribeckParametersX;
constexpr double kCoupling = 0.5;

PlanarArmPlant coupled_plant() {
  PlanarArmPlant plant;
  plant.seed = 11;
  plant.duration_s = 120.0;
  plant.motor2_coupling = kCoupling;
  return plant;
}

// Rows of the generator's model class, linear in θ = [A, D, B, I_a2, P1, P2, fc1, fv1, fc2, fv2]
// (tests/generator/planar_arm_generator.cpp with C = [1 0; c 1], no payload): M11 = A + 2B cos q₂
// + c²I_a2, M12 = D + B cos q₂ + c I_a2, M22 = D + I_a2, h = B sin q₂, G = −P1 cos q₁ −
// P2 cos(q₁+q₂) on joint 1, −P2 cos(q₁+q₂) on joint 2; motor 2's friction on q̇₂ + c q̇₁ through Cᵀ.
Eigen::Matrix<double, 2, 10> reference_rows(const offline::JointSamples& s, Eigen::Index k,
                                            double c) {
  const double q1 = s.q(k, 0), q2 = s.q(k, 1), v1 = s.dq(k, 0), v2 = s.dq(k, 1);
  const double a1 = s.ddq(k, 0), a2 = s.ddq(k, 1), motor = v2 + c * v1;
  auto sgn = [](double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); };
  const double co = std::cos(q2), si = std::sin(q2), g12 = -std::cos(q1 + q2);
  Eigen::Matrix<double, 2, 10> rows;
  rows.row(0) << a1, a2, 2 * co * a1 + co * a2 - si * (2 * v1 * v2 + v2 * v2), c * (c * a1 + a2),
      -std::cos(q1), g12, sgn(v1), v1, c * sgn(motor), c * motor;
  rows.row(1) << 0, a1 + a2, co * a1 + si * v1 * v1, c * a1 + a2, 0, g12, 0, 0, sgn(motor), motor;
  return rows;
}

// Plain least squares of the model class on the training moving rows: its residual per sample
// and its θ.
Eigen::MatrixXd reference_residual(const offline::JointSamples& s, double c,
                                   Eigen::VectorXd& theta) {
  std::vector<Eigen::Matrix<double, 1, 10>> a;
  std::vector<double> b;
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    if (s.heldout[k]) continue;
    const Eigen::Matrix<double, 2, 10> rows = reference_rows(s, k, c);
    for (int j = 0; j < 2; ++j)
      if (moving_sample(s, j, k)) {
        a.push_back(rows.row(j));
        b.push_back(s.effort(k, j));
      }
  }
  Eigen::MatrixXd A(static_cast<Eigen::Index>(a.size()), 10);
  Eigen::VectorXd B(A.rows());
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    A.row(i) = a[static_cast<std::size_t>(i)];
    B[i] = b[static_cast<std::size_t>(i)];
  }
  theta = A.colPivHouseholderQr().solve(B);
  Eigen::MatrixXd residual = Eigen::MatrixXd::Constant(s.size(), 2, std::nan(""));
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s.valid[k])
      residual.row(k) = (s.effort.row(k).transpose() - reference_rows(s, k, c) * theta).transpose();
  return residual;
}

double base_value(const NominalModelX& nominal, int column) {
  for (int i = 0; i < nominal.base_count; ++i)
    if (nominal.base_columns[i] == column) return nominal.base_values[i];
  return std::nan("");
}

TEST(IdentifyCoupled, RecoversTheCoupledMotorAndMatchesTheModelClassHeldOut) {
  const PlanarArmPlant plant = coupled_plant();
  const offline::Log log = generate_planar_log(plant);
  const auto model = load_robot<double, Eigen::Dynamic>(planar_coupled_robot_file());
  ASSERT_TRUE(model.coupled);
  ASSERT_EQ(model.coupling(1, 0), kCoupling);
  const offline::Identification id = offline::identify(log, model);
  const StribeckParametersX& f = id.nominal.friction;
  const PlanarArm arm;
  const double armature2 = base_value(id.nominal, 10 * 2 + 1);  // "Ia2": motor 2's
  const offline::JointSamples& s = id.samples;
  Eigen::VectorXd theta;  // [A, D, B, I_a2, P1, P2, fc1, fv1, fc2, fv2]
  const Eigen::MatrixXd reference_fit = reference_residual(s, kCoupling, theta);
  std::printf("identify: motor 1 τ_c %.4f b %.4f; motor 2 τ_c %.4f b %.4f I_a %.5f\n", f.coulomb[0],
              f.viscous[0], f.coulomb[1], f.viscous[1], armature2);
  std::printf(
      "model-class least squares: motor 1 τ_c %.4f b %.4f; motor 2 τ_c %.4f b %.4f "
      "I_a %.5f\n",
      theta[6], theta[7], theta[8], theta[9], theta[3]);
  // Motor 2 (coupled): the planted values.
  EXPECT_NEAR(f.coulomb[1], plant.coulomb_positive[1], 0.05 * plant.coulomb_positive[1]);
  EXPECT_NEAR(f.viscous[1], plant.viscous[1], 0.05 * plant.viscous[1]);
  EXPECT_NEAR(armature2, arm.armature, 0.05 * arm.armature);
  // Joint 1: its Dahl bristle (400 N·m/rad) tilts every Coulomb + viscous line fitted to this
  // log (τ_c ≈ 0.37, b ≈ 0.33 for 0.40, 0.30, the model-class fit as identify): the same as that
  // fit here; the planted values on a log without the memory (below).
  EXPECT_NEAR(f.coulomb[0], theta[6], 0.05 * theta[6]);
  EXPECT_NEAR(f.viscous[0], theta[7], 0.05 * theta[7]);

  const Eigen::Vector2d fitted = heldout_moving_rms(s, id.residual).rms;
  const Eigen::Vector2d reference = heldout_moving_rms(s, reference_fit).rms;
  std::printf("held-out moving RMS: identify %.4f %.4f, model-class least squares %.4f %.4f\n",
              fitted[0], fitted[1], reference[0], reference[1]);
  for (int j = 0; j < 2; ++j)
    EXPECT_LE(fitted[j], 1.2 * reference[j]) << "joint " << j + 1;

  // The same log fitted as if each motor drove its own joint: joint 2 is clearly worse.
  const auto uncoupled = load_robot<double, Eigen::Dynamic>(planar_robot_file());
  const offline::Identification plain = offline::identify(log, uncoupled);
  const Eigen::Vector2d without = heldout_moving_rms(plain.samples, plain.residual).rms;
  std::printf("held-out moving RMS without the coupling: %.4f %.4f\n", without[0], without[1]);
  EXPECT_GT(without[1], 2.0 * fitted[1]);
}

// Friction without presliding memory (stiff bristles: Coulomb + viscous): joint 1's planted
// friction and motor 2's armature within 5 %.
TEST(IdentifyCoupled, RecoversJointOneWithoutFrictionMemory) {
  PlanarArmPlant plant = coupled_plant();
  plant.bristle_stiffness = {1e5, 1e5};
  const auto model = load_robot<double, Eigen::Dynamic>(planar_coupled_robot_file());
  const offline::Identification id = offline::identify(generate_planar_log(plant), model);
  const StribeckParametersX& f = id.nominal.friction;
  const double armature2 = base_value(id.nominal, 10 * 2 + 1);
  std::printf("identify: motor 1 τ_c %.4f b %.4f; motor 2 τ_c %.4f b %.4f I_a %.5f\n", f.coulomb[0],
              f.viscous[0], f.coulomb[1], f.viscous[1], armature2);
  EXPECT_NEAR(f.coulomb[0], plant.coulomb_positive[0], 0.05 * plant.coulomb_positive[0]);
  EXPECT_NEAR(f.viscous[0], plant.viscous[0], 0.05 * plant.viscous[0]);
  EXPECT_NEAR(armature2, PlanarArm{}.armature, 0.05 * PlanarArm{}.armature);
}

// A coupled nominal model: friction = Cᵀ·f(C·q̇) in both the per-cycle and the regressor form; an
// uncoupled one unchanged bit for bit; the file keeps the coupled model's friction.
TEST(IdentifyCoupled, NominalModelTakesMotorFrictionThroughTheCoupling) {
  const auto coupled_model = load_robot<double, Eigen::Dynamic>(planar_coupled_robot_file());
  const auto plain_model = load_robot<double, Eigen::Dynamic>(planar_robot_file());
  StribeckParametersX friction;
  friction.resize(2);
  friction.coulomb << 0.4, 0.25;
  friction.static_friction << 0.5, 0.3;
  friction.stribeck_velocity << 0.05, 0.08;
  friction.viscous << 0.3, 0.2;
  const NominalModelX coupled = nominal_from_model(coupled_model, friction);
  const NominalModelX plain = nominal_from_model(plain_model, friction);
  DataX data(coupled.model);
  const Eigen::Vector2d q(0.3, -0.4), dq(0.7, -0.5), ddq(0.2, 0.1);
  Eigen::VectorXd rigid, tau_friction, rigid_r, friction_r;
  predict_effort(coupled, data, q, dq, ddq, rigid, tau_friction);
  predict_effort_by_regressor(coupled, data, q, dq, ddq, rigid_r, friction_r);
  const Eigen::Vector2d motor = coupled.model.coupling * dq;  // (0.7, −0.15)
  const Eigen::Vector2d expected =
      coupled.model.coupling.transpose() *
      stribeck_friction(friction, Eigen::VectorXd(motor), Eigen::VectorXd::Zero(2).eval());
  EXPECT_NEAR((tau_friction - expected).norm(), 0, 1e-12);
  EXPECT_NEAR((friction_r - expected).norm(), 0, 1e-12);
  EXPECT_NEAR((rigid - rigid_r).norm(), 0, 1e-9);

  DataX plain_data(plain.model);
  predict_effort(plain, plain_data, q, dq, ddq, rigid, tau_friction);
  const Eigen::VectorXd uncoupled =
      stribeck_friction(friction, Eigen::VectorXd(dq), Eigen::VectorXd::Zero(2).eval());
  for (int j = 0; j < 2; ++j)
    EXPECT_EQ(tau_friction[j], uncoupled[j]);  // the identity coupling: the same doubles

  const TempDir dir("coupled_nominal");
  save_nominal_model(dir / "coupled.params.json", coupled);
  const NominalModelX loaded =
      load_nominal_model(dir / "coupled.params.json", planar_coupled_robot_file());
  EXPECT_TRUE(loaded.model.coupled);
  EXPECT_EQ(loaded.friction.coulomb, friction.coulomb);
  EXPECT_EQ(loaded.friction.viscous, friction.viscous);
}

}  // namespace
}  // namespace tpf::test
