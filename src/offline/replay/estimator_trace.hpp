// The run-time estimator run over a whole log, every per-cycle quantity kept per row: the one
// source of the training features (trainer) and of the metrics (evaluate).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "offline/replay/recording_compensator.hpp"
#include "tpf/estimation/estimator.hpp"
#include "tpf/estimation/proprioceptive_estimate.hpp"
#include "tpf/kinematics/forward_kinematics.hpp"

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

/// Runs `estimator` (reset first) over `samples` in order and records every row. The compensator
/// must be a RecordingCompensator, whose last input is the row's TCN input.
template <typename S, int N, int P, typename Inner>
EstimatorTrace trace_estimator(Estimator<S, N, P, RecordingCompensator<Inner, S, N>>& estimator,
                               const std::vector<EstimatorSample<S, N, P>>& samples) {
  const auto T = static_cast<Eigen::Index>(samples.size());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EstimatorTrace tr;
  tr.t = Eigen::VectorXd::Constant(T, nan);
  tr.dq = Eigen::MatrixXd::Constant(T, N, nan);
  tr.inputs = Eigen::MatrixXd::Constant(T, kCompensatorInputsPerJoint * N, nan);
  tr.residual = tr.dq;
  tr.compensation = tr.dq;
  for (auto& e : tr.estimates)
    e = tr.dq;
  tr.proprioceptive = tr.dq;
  tr.external = tr.dq;
  tr.state = Eigen::VectorXi::Constant(T, -1);
  tr.contact = tr.state;
  tr.estimator_contact = tr.state;
  tr.pad = tr.state;
  tr.pad_force = Eigen::VectorXd::Constant(T, nan);
  tr.force_world = Eigen::MatrixXd::Constant(T, 3, nan);
  tr.wrench_valid = tr.state;
  tr.force_tactile = tr.force_world;
  tr.force_proprioceptive = tr.force_world;
  tr.torque_tactile = tr.dq;

  const auto& model = estimator.nominal().model;
  Data<S, N> data(model);
  Jacobian<S, N> J;
  ContactForceSettings<S> no_prior = estimator.parameters().wrench;
  no_prior.prior_floor_n = S(1e9);  // σ_Fn huge: the pad reading does not inform the solve
  no_prior.prior_relative = S(0);

  estimator.reset();
  for (Eigen::Index r = 0; r < T; ++r) {
    const auto& out = estimator.update(samples[static_cast<std::size_t>(r)]);
    if (out.status & (kStatusNonFiniteInput | kStatusStaleTime)) continue;
    tr.t[r] = double(out.t);
    tr.dq.row(r) = samples[static_cast<std::size_t>(r)].dq.transpose().template cast<double>();
    tr.inputs.row(r) = estimator.compensator().last_input.transpose().template cast<double>();
    tr.residual.row(r) = out.residual.transpose().template cast<double>();
    tr.compensation.row(r) = out.compensation.transpose().template cast<double>();
    for (int e = 0; e < kTorqueEstimatorCount; ++e) {
      const auto& est = out.estimates[static_cast<std::size_t>(e)];
      for (int j = 0; j < N; ++j)
        tr.estimates[static_cast<std::size_t>(e)](r, j) =
            (est.valid & (1u << j)) ? double(est.residual[j]) : nan;
    }
    const ExternalTorque<S, N> proprio = proprioceptive_estimate(out, estimator.parameters());
    tr.proprioceptive.row(r) = proprio.residual.transpose().template cast<double>();
    tr.external.row(r) = out.external.residual.transpose().template cast<double>();
    tr.state[r] = static_cast<int>(out.state);
    const auto& skin = estimator.skin();
    tr.contact[r] = skin.any_contact() ? 1 : 0;
    tr.estimator_contact[r] = out.contact ? 1 : 0;
    const int pad = skin.most_loaded();
    tr.pad[r] = pad;
    tr.pad_force[r] = pad >= 0 ? double(skin.normal_force(pad)) : 0.0;
    if (out.wrench.pad >= 0)
      tr.force_world.row(r) = out.wrench.force_world.transpose().template cast<double>();
    tr.wrench_valid[r] = out.wrench.pad >= 0 && out.wrench.valid ? 1 : 0;
    tr.torque_tactile.row(r).setZero();
    if (pad >= 0) {
      const auto& g = skin.geometry(pad);
      forward_kinematics(model, data, samples[static_cast<std::size_t>(r)].q);
      const Vector3<S> normal = pad_normal_in_world(data, g);
      tr.force_tactile.row(r) = (-tr.pad_force[r] * normal.template cast<double>()).transpose();
      point_jacobian(model, data, g.link, pad_point_in_world(data, g), J);
      tr.torque_tactile.row(r) = (J.template topRows<3>().transpose().template cast<double>() *
                                  tr.force_tactile.row(r).transpose())
                                     .transpose();
      const ContactForce<S> f = estimate_contact_force(J, pad_contact_frame_in_world(data, g),
                                                       proprio.torque, S(0), no_prior);
      tr.force_proprioceptive.row(r) = f.force_world.transpose().template cast<double>();
    }
  }
  return tr;
}

}  // namespace tpf::offline
