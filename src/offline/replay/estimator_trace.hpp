// The run-time estimator run over a whole log, every per-cycle quantity kept per row: the one
// source of the training features (trainer) and of the metrics (evaluate).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "tpf/estimation/compensator.hpp"
#include "tpf/estimation/estimator_types.hpp"

namespace tpf::offline {

/// Per row of the log (T rows, N joints). Rows the estimator skipped (non-finite or stale input)
/// are NaN (−1 for the integer columns). Effort-unit columns are in the nominal model's unit.
struct EstimatorTrace {
  Eigen::VectorXd t;             ///< [s]
  Eigen::MatrixXd dq;            ///< T × N [rad/s], the sample's
  Eigen::MatrixXd inputs;        ///< T × 5N, exactly what the compensator received
  Eigen::MatrixXd residual;      ///< T × N, τ_res = τ_meas − τ_dyn − τ_fric (nominal)
  Eigen::MatrixXd compensation;  ///< T × N, τ_TCN
  /// Per TorqueEstimator: the external residual after its dead band, T × N; NaN where the
  /// estimator gave no estimate (StaticModelFree on moving joints).
  std::array<Eigen::MatrixXd, kTorqueEstimatorCount> estimates;
  /// T × N: the proprioceptive-only baseline's residual after its dead band
  /// (proprioceptive_estimate of each row's output).
  Eigen::MatrixXd proprioceptive;
  Eigen::MatrixXd external;           ///< T × N, EstimatorOutput::external.residual (the fusion)
  Eigen::VectorXi state;              ///< ContactState as int
  Eigen::VectorXi contact;            ///< skin: 1 while a pad is in contact
  Eigen::VectorXi estimator_contact;  ///< EstimatorOutput::contact: a pad or the torque alarm
  Eigen::VectorXi pad;                ///< most loaded pad in contact (0-based), −1 none
  Eigen::VectorXd pad_force;          ///< its normal-force reading [N] (0 without contact)
  Eigen::MatrixXd force_world;        ///< T × 3, the fused wrench's force [N], world frame
  Eigen::VectorXi wrench_valid;       ///< 1 when the force is observable (shear included)
  /// T × 3 [N], world frame, at the same pad: the tactile-only force −F_n·n (the pad's normal
  /// reading along its inward normal, no shear) and the proprioceptive-only force (least squares
  /// of the Proprioceptive torque through the pad's contact Jacobian, no pad prior; the contact
  /// location is granted to it).
  Eigen::MatrixXd force_tactile;
  Eigen::MatrixXd force_proprioceptive;
  /// T × N [N·m]: the tactile-only external torque J_vᵀ·(−F_n·n) at the pad (0 without contact).
  Eigen::MatrixXd torque_tactile;

  Eigen::Index rows() const { return t.size(); }
};

/// The combined external residual (T × N): StaticModelFree where it has an estimate (resting
/// joints), Fused elsewhere — what the estimator's torque-only contact alarm watches.
inline Eigen::MatrixXd combined_external(const EstimatorTrace& tr) {
  const auto& fixed = tr.estimates[static_cast<int>(TorqueEstimator::StaticModelFree)];
  const auto& fused = tr.estimates[static_cast<int>(TorqueEstimator::Fused)];
  return fixed.array().isFinite().select(fixed, fused);
}

/// Per row of a T × N estimate after its dead band: is it outside the band (nonzero) on some
/// joint? 0 on rows without an estimate (NaN).
inline Eigen::VectorXi any_joint_outside_band(const Eigen::MatrixXd& estimate) {
  Eigen::VectorXi e = Eigen::VectorXi::Zero(estimate.rows());
  for (Eigen::Index k = 0; k < estimate.rows(); ++k)
    for (Eigen::Index j = 0; j < estimate.cols(); ++j)
      if (std::isfinite(estimate(k, j)) && estimate(k, j) != 0.0) e[k] = 1;
  return e;
}

}  // namespace tpf::offline
