// The estimator's per-cycle input (one sample) and output.
#pragma once

#include <array>
#include <cstdint>

#include "tpf/common/types.hpp"
#include "tpf/estimation/contact_force.hpp"
#include "tpf/estimation/contact_state.hpp"

namespace tpf {

/// One sample of the robot, as a row of the log format (docs/log-format.md): N joints, P pads
/// (0: no skin).
template <typename S, int N, int P>
struct EstimatorSample {
  S t = S(0);                                        ///< [s], must increase
  JointVector<S, N> q = JointVector<S, N>::Zero();   ///< [rad]
  JointVector<S, N> dq = JointVector<S, N>::Zero();  ///< [rad/s]
  /// τ_meas [N·m]: joint torque the drive produces (motor current through torque_from_current)
  JointVector<S, N> effort = JointVector<S, N>::Zero();
  /// Pad gauge pressure [kPa]; P = Eigen::Dynamic: empty until sized (the offline tools).
  Eigen::Matrix<S, P, 1> pressure = Eigen::Matrix<S, P, 1>::Zero(P == Eigen::Dynamic ? 0 : P);
  JointVector<S, N> ddq = JointVector<S, N>::Zero();  ///< [rad/s²], used only when has_ddq
  bool has_ddq = false;
};

/// The two external-torque estimates the estimator combines (EstimatorOutput::external). The
/// proprioceptive-only baseline an evaluation compares them with is not computed per cycle:
/// proprioceptive_estimate (proprioceptive_estimate.hpp) derives it from an output.
enum class TorqueEstimator : std::uint8_t {
  StaticModelFree,  ///< Δτ_res = τ_res − τ̂_fric,s on static joints, noise dead band
  Fused,            ///< τ_meas − (τ_dyn + τ_fric + τ_TCN), dead band 1.5·σ_fused
};
inline constexpr int kTorqueEstimatorCount = 2;

/// The valid mask of an estimate on every joint of an N-joint arm (bit j: joint j).
template <int N>
inline constexpr std::uint32_t kEveryJoint = N == 32 ? ~0u : (1u << N) - 1;

/// One external-torque estimate. Sign: τ_ext is what the environment applies to the robot, so
/// residual = −τ_ext (a push in +q lowers the effort).
template <typename S, int N>
struct ExternalTorque {
  JointVector<S, N> residual = JointVector<S, N>::Zero();  ///< after the dead band [N·m]
  JointVector<S, N> torque = JointVector<S, N>::Zero();    ///< τ_ext [N·m]
  std::uint32_t valid = 0;                                 ///< bit j: joint j has an estimate
};

/// Everything one update computes. Torques in N·m.
template <typename S, int N>
struct EstimatorOutput {
  S t = S(0);
  std::uint32_t status = 0;  ///< EstimatorStatus bits
  ContactState state = ContactState::Dynamic;
  JointVector<S, N> ddq = JointVector<S, N>::Zero();              ///< used q̈ [rad/s²]
  JointVector<S, N> effort_rigid = JointVector<S, N>::Zero();     ///< τ_dyn
  JointVector<S, N> effort_friction = JointVector<S, N>::Zero();  ///< τ_fric (nominal)
  JointVector<S, N> residual = JointVector<S, N>::Zero();  ///< τ_res = τ_meas − τ_dyn − τ_fric
  JointVector<S, N> static_friction = JointVector<S, N>::Zero();  ///< τ̂_fric,s (0 when moving)
  JointVector<S, N> compensation = JointVector<S, N>::Zero();     ///< τ_TCN
  std::array<ExternalTorque<S, N>, kTorqueEstimatorCount> estimates{};  ///< by TorqueEstimator
  /// The estimator's answer (fusion of both senses): with exactly one pad in contact, the torque
  /// of the fused contact force, J_vᵀ·wrench.force_world (no dead band: the pad gates it);
  /// otherwise StaticModelFree where valid and Fused elsewhere, each after its dead band.
  ExternalTorque<S, N> external;
  ContactForce<S> wrench;  ///< at the most loaded pad in contact (pad = −1: none)
  /// Contact believed: a pad in contact, or (contacts off the pads) the combined external torque
  /// outside its dead band for parameters.torque_alarm_samples cycles in a row.
  bool contact = false;

  const ExternalTorque<S, N>& estimate(TorqueEstimator e) const noexcept {
    return estimates[static_cast<int>(e)];
  }
};

}  // namespace tpf
