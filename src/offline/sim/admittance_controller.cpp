#include "offline/sim/admittance_controller.hpp"

#include <algorithm>
#include <cmath>

namespace tpf::offline {

namespace {
constexpr double kContactThresholdKpa = 0.6;
constexpr double kBaselineTimeConstant = 0.5;  // s
constexpr double kMaxSpeed = 1.0;              // rad/s
}  // namespace

AdmittanceController::AdmittanceController(const TeachingConfig& config,
                                           const TwinFriction& nominal_friction,
                                           const TwinVector& start, const TwinVector& lower,
                                           const TwinVector& upper)
    : config_(config),
      friction_(nominal_friction),
      lower_(lower),
      upper_(upper),
      q_ref_(start),
      dq_ref_(TwinVector::Zero(start.size())),
      baseline_(TwinVector::Zero(start.size())) {
  for (JointFriction& p : friction_.joints) {
    p.stribeck.load_coulomb.setZero();
    p.stribeck.load_viscous.setZero();
  }
}

TwinVector AdmittanceController::nominal_friction(const TwinVector& dq) const {
  // smooth_stribeck_friction of tpf::core, joint by joint, at zero load.
  TwinVector tau(dq.size());
  for (int j = 0; j < dq.size(); ++j) {
    const auto& p = friction_[j].stribeck;
    tau[j] =
        stribeck_level(p, 0, dq[j], 0.0) * std::tanh(dq[j] / kDefaultFrictionSmoothing<double>) +
        viscous_coefficient(p, 0, 0.0) * dq[j];
  }
  return tau;
}

void AdmittanceController::update(const TwinArm& nominal, const TwinVector& q, const TwinVector& dq,
                                  const TwinVector& current_ma, double max_pad_kpa, double dt) {
  TwinVector motor = nominal.torque_constant().cwiseProduct(current_ma) / 1000.0;
  TwinVector friction;
  if (nominal.coupled()) {
    // Coupled motors: their torques and their curves on their velocities, through Cᵀ.
    const TwinMatrix& c = nominal.coupling();
    motor = c.transpose() * motor;
    friction = c.transpose() * nominal_friction(c * dq);
  } else {
    friction = nominal_friction(dq);
  }
  const TwinVector raw = -(motor - nominal.gravity(q) - friction);
  const bool contact = max_pad_kpa > kContactThresholdKpa;
  if (!baseline_ready_) {
    baseline_ = raw;
    baseline_ready_ = true;
  } else if (!contact && dq_ref_.cwiseAbs().maxCoeff() < 1e-3) {
    baseline_ += (dt / kBaselineTimeConstant) * (raw - baseline_);
  }
  TwinVector tau = TwinVector::Zero(raw.size());
  if (contact) {
    for (int j = 0; j < raw.size(); ++j) {
      const double e = raw[j] - baseline_[j];
      tau[j] = std::abs(e) > config_.dead_band_nm ? e - std::copysign(config_.dead_band_nm, e) : 0;
    }
  }
  integrate(tau, dt);
}

void AdmittanceController::follow(const TwinVector& tau_ext, double max_pad_kpa, double dt) {
  integrate(
      max_pad_kpa > kContactThresholdKpa ? tau_ext : TwinVector(TwinVector::Zero(q_ref_.size())),
      dt);
}

void AdmittanceController::goal(double since_write, TwinVector& q_goal, TwinVector& dq_goal) const {
  q_goal = q_ref_ + since_write * dq_ref_;
  dq_goal = dq_ref_;
  for (int j = 0; j < q_ref_.size(); ++j) {
    if (q_goal[j] < lower_[j] || q_goal[j] > upper_[j]) {
      q_goal[j] = std::clamp(q_goal[j], lower_[j], upper_[j]);
      dq_goal[j] = 0.0;
    }
  }
}

void AdmittanceController::integrate(const TwinVector& tau, double dt) {
  const TwinVector ddq = (tau - config_.admittance_damping * dq_ref_) / config_.admittance_inertia;
  dq_ref_ = (dq_ref_ + dt * ddq).cwiseMax(-kMaxSpeed).cwiseMin(kMaxSpeed);
  q_ref_ += dt * dq_ref_;
  for (int j = 0; j < q_ref_.size(); ++j) {
    if (q_ref_[j] < lower_[j] || q_ref_[j] > upper_[j]) {
      q_ref_[j] = std::clamp(q_ref_[j], lower_[j], upper_[j]);
      dq_ref_[j] = 0.0;
    }
  }
}

}  // namespace tpf::offline
