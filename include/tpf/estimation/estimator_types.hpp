// The estimator's per-cycle input (one sample) and output.
#pragma once

#include <array>
#include <cstdint>

#include "tpf/common/types.hpp"
#include "tpf/estimation/contact_force.hpp"
#include "tpf/estimation/contact_state.hpp"

namespace tpf {

/// One sample of the robot, as a row of the log format (docs/log-format.md): N joints, P pads
/// (0: no skin). At Eigen::Dynamic (joints or pads) the vectors are empty until resize().
template <typename S, int N, int P>
struct EstimatorSample {
  S t = S(0);                                                 ///< [s], must increase
  JointVector<S, N> q = zero_or_empty<JointVector<S, N>>();   ///< [rad]
  JointVector<S, N> dq = zero_or_empty<JointVector<S, N>>();  ///< [rad/s]
  /// τ_meas [N·m]: joint torque the drive produces (motor current through torque_from_current)
  JointVector<S, N> effort = zero_or_empty<JointVector<S, N>>();
  /// Pad gauge pressure [kPa]; P = Eigen::Dynamic: empty until sized (the offline tools).
  Eigen::Matrix<S, P, 1> pressure = zero_or_empty<Eigen::Matrix<S, P, 1>>();
  JointVector<S, N> ddq = zero_or_empty<JointVector<S, N>>();  ///< [rad/s²], used only when has_ddq
  bool has_ddq = false;

  /// Zeros for `joints` joints and `pads` pads (each must equal N, P where those are fixed).
  void resize(int joints, int pads) {
    q = dq = effort = ddq = JointVector<S, N>::Zero(joints);
    pressure = Eigen::Matrix<S, P, 1>::Zero(pads);
  }
};

/// The two external-torque estimates the estimator combines (EstimatorOutput::external). The
/// proprioceptive-only baseline an evaluation compares them with is not computed per cycle:
/// proprioceptive_estimate (proprioceptive_estimate.hpp) derives it from an output.
enum class TorqueEstimator : std::uint8_t {
  StaticModelFree,  ///< Δτ_res = τ_res − τ̂_fric,s on static joints, noise dead band
  Fused,            ///< τ_meas − (τ_dyn + τ_fric + τ_TCN), dead band 1.5·σ_fused
};
inline constexpr int kTorqueEstimatorCount = 2;

/// The valid mask of an estimate on every joint of a `joints`-joint arm (bit j: joint j; at most
/// 32 joints).
constexpr std::uint32_t every_joint_mask(int joints) noexcept {
  return joints >= 32 ? ~0u : (std::uint32_t(1) << joints) - 1u;
}

/// One external-torque estimate. Sign: τ_ext is what the environment applies to the robot, so
/// residual = −τ_ext (a push in +q lowers the effort).
template <typename S, int N>
struct ExternalTorque {
  JointVector<S, N> residual = zero_or_empty<JointVector<S, N>>();  ///< after the dead band [N·m]
  JointVector<S, N> torque = zero_or_empty<JointVector<S, N>>();    ///< τ_ext [N·m]
  std::uint32_t valid = 0;  ///< bit j: joint j has an estimate

  /// Zeros for `joints` joints (N where N is fixed), no joint valid.
  void resize(int joints) {
    residual.resize(joints);
    torque.resize(joints);
    clear();
  }
  /// Zeros, no joint valid, the size kept (allocation-free).
  void clear() noexcept {
    residual.setZero();
    torque.setZero();
    valid = 0;
  }
};

/// Everything one update computes. Torques in N·m. At Eigen::Dynamic the vectors are empty until
/// resize() (the estimator sizes its own at construction).
template <typename S, int N>
struct EstimatorOutput {
  using Vector = JointVector<S, N>;
  S t = S(0);
  std::uint32_t status = 0;  ///< EstimatorStatus bits
  ContactState state = ContactState::Dynamic;
  Vector ddq = zero_or_empty<Vector>();              ///< used q̈ [rad/s²]
  Vector effort_rigid = zero_or_empty<Vector>();     ///< τ_dyn
  Vector effort_friction = zero_or_empty<Vector>();  ///< τ_fric (nominal)
  Vector residual = zero_or_empty<Vector>();         ///< τ_res = τ_meas − τ_dyn − τ_fric
  Vector static_friction = zero_or_empty<Vector>();  ///< τ̂_fric,s (0 when moving)
  Vector compensation = zero_or_empty<Vector>();     ///< τ_TCN
  std::array<ExternalTorque<S, N>, kTorqueEstimatorCount> estimates{};  ///< by TorqueEstimator
  /// The estimator's answer (fusion of both senses): with exactly one pad in contact, the torque
  /// of the fused contact force, J_vᵀ·wrench.force_world (no dead band: the pad gates it);
  /// otherwise StaticModelFree where valid and Fused elsewhere, each after its dead band.
  ExternalTorque<S, N> external;
  ContactForce<S> wrench;  ///< at the most loaded pad in contact (pad = −1: none)
  /// Contact believed: a pad in contact, or (contacts off the pads) the combined external torque
  /// outside its dead band for parameters.torque_alarm_samples cycles in a row.
  bool contact = false;

  /// The initial output of a `joints`-joint arm (N where N is fixed): zeros, nothing valid.
  void resize(int joints) {
    for (Vector* v :
         {&ddq, &effort_rigid, &effort_friction, &residual, &static_friction, &compensation})
      v->resize(joints);
    for (ExternalTorque<S, N>& e : estimates)
      e.resize(joints);
    external.resize(joints);
    clear();
  }
  /// The initial output with the size kept (allocation-free): zeros, nothing valid, no contact.
  void clear() noexcept {
    t = S(0);
    status = 0;
    state = ContactState::Dynamic;
    for (Vector* v :
         {&ddq, &effort_rigid, &effort_friction, &residual, &static_friction, &compensation})
      v->setZero();
    for (ExternalTorque<S, N>& e : estimates)
      e.clear();
    external.clear();
    wrench = ContactForce<S>{};
    contact = false;
  }

  const ExternalTorque<S, N>& estimate(TorqueEstimator e) const noexcept {
    return estimates[static_cast<int>(e)];
  }
};

}  // namespace tpf
