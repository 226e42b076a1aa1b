#include "offline/sim/twin_plant.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "tpf/common/error.hpp"

namespace tpf::offline {

namespace {
// Smoothing velocity of the memoryless Stribeck option (rad/s): well below any motion speed.
constexpr double kStribeckSmoothing = 1e-3;
constexpr int kNewtonIterations = 8;
}  // namespace

TwinPlant::TwinPlant(const TwinArm& arm, const TwinFriction& friction, const EffectsConfig& effects,
                     double dt)
    : arm_(arm),
      friction_parameters_(friction),
      effects_(effects),
      dt_(dt),
      n_(arm.joints()),
      coupled_(arm.coupled()) {
  if (friction_parameters_.count() != n_)
    throw Error("TwinPlant: the friction parameters are for " +
                std::to_string(friction_parameters_.count()) + " joints, the arm has " +
                std::to_string(n_));
  if (!effects_.load_dependent_friction) {
    for (JointFriction& p : friction_parameters_.joints) {
      p.stribeck.load_coulomb.setZero();
      p.stribeck.load_viscous.setZero();
    }
  }
  reset(TwinVector::Zero(n_), TwinVector::Zero(n_));
  for (TwinVector* v : {&q0_, &dq0_, &a1_, &a2_, &a3_, &a4_, &v2_, &v3_, &v4_, &q_stage_,
                        &tau_stage_, &abs_gravity_, &v0_, &delta_, &force_, &slope_, &newton_step_,
                        &motor_velocity_, &motor_friction_})
    v->setZero(n_);
  mass_.setZero(n_, n_);
  newton_matrix_.setZero(n_, n_);
}

void TwinPlant::reset(const TwinVector& q, const TwinVector& dq) {
  q_ = q;
  dq_ = dq;
  ddq_.setZero(n_);
  friction_.setZero(n_);
  motor_friction_.setZero(n_);
  bristles_.setZero(n_);
}

TwinVector TwinPlant::position_torque(const TwinVector& q) const {
  TwinVector tau(n_);
  position_torque(q, tau);
  return tau;
}

void TwinPlant::position_torque(const TwinVector& q, TwinVector& tau) const {
  tau.setZero(n_);
  if (effects_.ripple.enabled)
    for (int j = 0; j < n_; ++j)
      tau[j] += effects_.ripple.amplitude[j] *
                std::sin(effects_.ripple.cycles_per_rev[j] * q[j] + effects_.ripple.phase[j]);
  if (effects_.spring.enabled)
    tau -= effects_.spring.stiffness.cwiseProduct(q - effects_.spring.neutral);
}

void TwinPlant::acceleration(const TwinVector& q, const TwinVector& dq, const TwinVector& tau_in,
                             TwinVector& ddq) {
  position_torque(q, tau_stage_);
  tau_stage_ = tau_in + tau_stage_;  // coefficient-wise: τ_in[j] + τ_pos[j], as before
  arm_.forward_dynamics(q, dq, tau_stage_, ddq);
}

double TwinPlant::joint_friction(int j, double v, double abs_gravity, double viscous_scale,
                                 double* z_out) const {
  const JointFriction& p = friction_parameters_[j];
  // Temperature scales the whole viscous term (b + α_v|G|)·v, which is additive in both models.
  const double viscous_change =
      (viscous_scale - 1.0) * viscous_coefficient(p.stribeck, 0, abs_gravity) * v;
  if (effects_.friction == EffectsConfig::Friction::kLuGre) {
    const auto step = lugre_joint_step(p, 0, bristles_[j], v, abs_gravity, dt_);
    if (z_out) *z_out = step.z;
    return step.torque + viscous_change;
  }
  if (z_out) *z_out = 0.0;
  return stribeck_level(p.stribeck, 0, v, abs_gravity) * std::tanh(v / kStribeckSmoothing) +
         viscous_coefficient(p.stribeck, 0, abs_gravity) * v + viscous_change;
}

void TwinPlant::step(const TwinVector& tau_in, const TwinVector& viscous_scale) {
  // The expressions of the by-value formulation, evaluated into the members: same values, same
  // order of operations, bit for bit (the twin's logs are pinned to its rounding).
  const double h = dt_;
  q0_ = q_;
  dq0_ = dq_;
  const TwinVector &q0 = q0_, &dq0 = dq0_;
  // 1. RK4 of the smooth dynamics.
  acceleration(q0, dq0, tau_in, a1_);
  v2_ = dq0 + 0.5 * h * a1_;
  q_stage_ = q0 + 0.5 * h * dq0;
  acceleration(q_stage_, v2_, tau_in, a2_);
  v3_ = dq0 + 0.5 * h * a2_;
  q_stage_ = q0 + 0.5 * h * v2_;
  acceleration(q_stage_, v3_, tau_in, a3_);
  v4_ = dq0 + h * a3_;
  q_stage_ = q0 + h * v3_;
  acceleration(q_stage_, v4_, tau_in, a4_);
  TwinVector& q = q_;
  TwinVector& dq = dq_;
  q = q0 + (h / 6.0) * (dq0 + 2.0 * v2_ + 2.0 * v3_ + v4_);
  dq = dq0 + (h / 6.0) * (a1_ + 2.0 * a2_ + 2.0 * a3_ + a4_);

  // 2. Implicit friction impulse.
  if (effects_.friction != EffectsConfig::Friction::kNone) {
    TwinVector& abs_gravity = abs_gravity_;
    abs_gravity.setZero();
    if (effects_.load_dependent_friction) abs_gravity = arm_.gravity(q0).cwiseAbs();
    mass_ = arm_.mass_matrix(q);
    v0_ = (q - q0) / h;
    if (coupled_)
      coupled_friction_step(abs_gravity, viscous_scale);
    else
      joint_friction_step(abs_gravity, viscous_scale);
    q += 0.5 * h * delta_;
    dq += delta_;
  } else {
    friction_.setZero();
    motor_friction_.setZero();
  }
  ddq_ = (dq - dq0) / h;
}

void TwinPlant::joint_friction_step(const TwinVector& abs_gravity,
                                    const TwinVector& viscous_scale) {
  const double h = dt_;
  const TwinMatrix& M = mass_;
  const TwinVector& v0 = v0_;
  TwinVector &delta = delta_, &force = force_, &slope = slope_;
  delta.setZero();
  for (int it = 0; it < kNewtonIterations; ++it) {
    for (int j = 0; j < n_; ++j) {
      const double v = v0[j] + 0.5 * delta[j];
      const double e = 1e-7 * (1.0 + std::abs(v));
      force[j] = joint_friction(j, v, abs_gravity[j], viscous_scale[j], nullptr);
      slope[j] = (joint_friction(j, v + e, abs_gravity[j], viscous_scale[j], nullptr) -
                  joint_friction(j, v - e, abs_gravity[j], viscous_scale[j], nullptr)) /
                 (2 * e);
    }
    // M·δ by twin_linear_algebra.hpp, then the sum: in one expression Eigen would accumulate
    // M·δ into h·F, and the twin's logs must not depend on Eigen's kernels.
    TwinVector& step = newton_step_;  // the residual M·δ + h·F, then the Newton step
    multiply(M, delta, step);
    step += h * force;
    TwinMatrix& J = newton_matrix_;
    J = M;
    J.diagonal() += 0.5 * h * slope.cwiseMax(0.0);
    newton_factor_.compute(J);
    newton_factor_.solve_in_place(step);
    delta -= step;
    if (step.cwiseAbs().maxCoeff() < 1e-13 * (1.0 + v0.cwiseAbs().maxCoeff())) break;
  }
  for (int j = 0; j < n_; ++j)
    friction_[j] =
        joint_friction(j, v0[j] + 0.5 * delta[j], abs_gravity[j], viscous_scale[j], &bristles_[j]);
}

void TwinPlant::coupled_friction_step(const TwinVector& abs_gravity,
                                      const TwinVector& viscous_scale) {
  const double h = dt_;
  const TwinMatrix& M = mass_;
  const TwinMatrix& C = arm_.coupling();
  const TwinVector& v0 = v0_;
  TwinVector &delta = delta_, &u = motor_velocity_, &force = force_, &slope = slope_;
  // u = C·(v0 + δ/2): the motors' mean velocities over the step (output scale).
  const auto motor_velocities = [&] {
    for (int m = 0; m < n_; ++m) {
      double sum = 0.0;
      for (int j = 0; j < n_; ++j)
        sum += C(m, j) * (v0[j] + 0.5 * delta[j]);
      u[m] = sum;
    }
  };
  delta.setZero();
  for (int it = 0; it < kNewtonIterations; ++it) {
    motor_velocities();
    for (int m = 0; m < n_; ++m) {
      const double e = 1e-7 * (1.0 + std::abs(u[m]));
      force[m] = joint_friction(m, u[m], abs_gravity[m], viscous_scale[m], nullptr);
      slope[m] = (joint_friction(m, u[m] + e, abs_gravity[m], viscous_scale[m], nullptr) -
                  joint_friction(m, u[m] - e, abs_gravity[m], viscous_scale[m], nullptr)) /
                 (2 * e);
    }
    // The residual M·δ + h·Cᵀ·F(u), then the Newton step on M + ½h·Cᵀ·diag(max(F', 0))·C.
    TwinVector& step = newton_step_;
    multiply(M, delta, step);
    for (int j = 0; j < n_; ++j) {
      double joint_force = 0.0;
      for (int m = 0; m < n_; ++m)
        joint_force += C(m, j) * force[m];
      step[j] += h * joint_force;
    }
    TwinMatrix& J = newton_matrix_;
    J = M;
    for (int m = 0; m < n_; ++m) {
      const double w = 0.5 * h * std::max(slope[m], 0.0);
      if (w == 0.0) continue;
      for (int i = 0; i < n_; ++i) {
        if (C(m, i) == 0.0) continue;
        for (int j = 0; j < n_; ++j)
          J(i, j) += w * C(m, i) * C(m, j);
      }
    }
    newton_factor_.compute(J);
    newton_factor_.solve_in_place(step);
    delta -= step;
    if (step.cwiseAbs().maxCoeff() < 1e-13 * (1.0 + v0.cwiseAbs().maxCoeff())) break;
  }
  motor_velocities();
  for (int m = 0; m < n_; ++m)
    motor_friction_[m] = joint_friction(m, u[m], abs_gravity[m], viscous_scale[m], &bristles_[m]);
  for (int j = 0; j < n_; ++j) {
    double joint_force = 0.0;
    for (int m = 0; m < n_; ++m)
      joint_force += C(m, j) * motor_friction_[m];
    friction_[j] = joint_force;
  }
}

}  // namespace tpf::offline
