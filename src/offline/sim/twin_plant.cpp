#include "offline/sim/twin_plant.hpp"

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
    : arm_(arm), friction_parameters_(friction), effects_(effects), dt_(dt), n_(arm.joints()) {
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
}

void TwinPlant::reset(const TwinVector& q, const TwinVector& dq) {
  q_ = q;
  dq_ = dq;
  ddq_.setZero(n_);
  friction_.setZero(n_);
  bristles_.setZero(n_);
}

TwinVector TwinPlant::position_torque(const TwinVector& q) const {
  TwinVector tau = TwinVector::Zero(n_);
  if (effects_.ripple.enabled)
    for (int j = 0; j < n_; ++j)
      tau[j] += effects_.ripple.amplitude[j] *
                std::sin(effects_.ripple.cycles_per_rev[j] * q[j] + effects_.ripple.phase[j]);
  if (effects_.spring.enabled)
    tau -= effects_.spring.stiffness.cwiseProduct(q - effects_.spring.neutral);
  return tau;
}

TwinVector TwinPlant::acceleration(const TwinVector& q, const TwinVector& dq,
                                   const TwinVector& tau_in) {
  return arm_.forward_dynamics(q, dq, tau_in + position_torque(q));
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
  const double h = dt_;
  const TwinVector q0 = q_, dq0 = dq_;
  // 1. RK4 of the smooth dynamics.
  const TwinVector a1 = acceleration(q0, dq0, tau_in);
  const TwinVector v2 = dq0 + 0.5 * h * a1;
  const TwinVector a2 = acceleration(q0 + 0.5 * h * dq0, v2, tau_in);
  const TwinVector v3 = dq0 + 0.5 * h * a2;
  const TwinVector a3 = acceleration(q0 + 0.5 * h * v2, v3, tau_in);
  const TwinVector v4 = dq0 + h * a3;
  const TwinVector a4 = acceleration(q0 + h * v3, v4, tau_in);
  TwinVector q = q0 + (h / 6.0) * (dq0 + 2.0 * v2 + 2.0 * v3 + v4);
  TwinVector dq = dq0 + (h / 6.0) * (a1 + 2.0 * a2 + 2.0 * a3 + a4);

  // 2. Implicit friction impulse.
  if (effects_.friction != EffectsConfig::Friction::kNone) {
    TwinVector abs_gravity = TwinVector::Zero(n_);
    if (effects_.load_dependent_friction) abs_gravity = arm_.gravity(q0).cwiseAbs();
    const TwinMatrix M = arm_.mass_matrix(q);
    const TwinVector v0 = (q - q0) / h;
    TwinVector delta = TwinVector::Zero(n_), force(n_), slope(n_);
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
      const TwinVector residual = multiply(M, delta) + h * force;
      TwinMatrix J = M;
      J.diagonal() += 0.5 * h * slope.cwiseMax(0.0);
      newton_factor_.compute(J);
      const TwinVector step = newton_factor_.solve(residual);
      delta -= step;
      if (step.cwiseAbs().maxCoeff() < 1e-13 * (1.0 + v0.cwiseAbs().maxCoeff())) break;
    }
    for (int j = 0; j < n_; ++j)
      friction_[j] = joint_friction(j, v0[j] + 0.5 * delta[j], abs_gravity[j], viscous_scale[j],
                                    &bristles_[j]);
    q += 0.5 * h * delta;
    dq += delta;
  } else {
    friction_.setZero();
  }
  ddq_ = (dq - dq0) / h;
  q_ = q;
  dq_ = dq;
}

}  // namespace tpf::offline
