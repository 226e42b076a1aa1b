#include "offline/sim/ph54_drive.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tpf::offline {

Ph54Drive::Ph54Drive(const DriveConfig& config, const TwinVector& inertia,
                     const TwinVector& torque_constant, const TwinVector& current_limit,
                     const TwinVector& velocity_limit)
    : config_(config), current_limit_(current_limit), velocity_limit_(velocity_limit) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  kp_.setConstant(inertia.size(), two_pi * config.position_bandwidth_hz);
  kv_ = (two_pi * config.velocity_bandwidth_hz) * inertia.cwiseQuotient(torque_constant);
  ki_ = (two_pi * config.integral_corner_hz) * kv_;
  integral_.setZero(inertia.size());
  current_.setZero(inertia.size());
}

void Ph54Drive::reset(const TwinVector& current) {
  integral_ = config_.enabled ? current : TwinVector(TwinVector::Zero(current.size()));
  current_ = integral_;
}

const TwinVector& Ph54Drive::update(const TwinVector& q_ref, const TwinVector& dq_ref,
                                    const TwinVector& q, const TwinVector& dq, double dt) {
  if (!config_.enabled) {
    current_.setZero();
    return current_;
  }
  const double lag =
      config_.current_time_constant > 0 ? 1.0 - std::exp(-dt / config_.current_time_constant) : 1.0;
  for (int j = 0; j < current_.size(); ++j) {
    double v_cmd = config_.velocity_feedforward * dq_ref[j] + kp_[j] * (q_ref[j] - q[j]);
    v_cmd = std::clamp(v_cmd, -velocity_limit_[j], velocity_limit_[j]);
    const double error = v_cmd - dq[j];
    const double proportional = kv_[j] * error;
    // Conditional integration (anti-windup): stop integrating into the current limit.
    const double candidate = integral_[j] + ki_[j] * error * dt;
    const double limit = current_limit_[j];
    if (std::abs(candidate + proportional) <= limit || std::abs(candidate) < std::abs(integral_[j]))
      integral_[j] = std::clamp(candidate, -limit, limit);
    const double command = std::clamp(proportional + integral_[j], -limit, limit);
    current_[j] += lag * (command - current_[j]);
  }
  return current_;
}

}  // namespace tpf::offline
