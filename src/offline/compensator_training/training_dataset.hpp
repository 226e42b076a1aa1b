// TCN training data from estimator traces of contact-free logs.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/compensator_training/tcn_trainer.hpp"
#include "offline/regimes/regime.hpp"
#include "offline/replay/estimator_trace.hpp"

namespace tpf::offline {

/// One training sequence from the trace of a contact-free log (N joints):
///   inputs   = the compensator inputs the estimator built, x = [q; q̇; q̈; τ̂_fric,s; τ_fric,nom]
///              (T × 5N), or for joint ≥ 0 that joint's five columns
///              [q_j, q̇_j, q̈_j, τ̂_fric,s,j, τ_fric,nom,j] (T × 5);
///   residual = τ_res = τ_meas − predict_effort(q, q̇, q̈) [N·m] (T × N, or T × 1 for one
///              joint): the friction the nominal model misses (O(1) in N·m, as Adam likes it).
/// Rows the estimator skipped stay NaN: the trainer cuts the sequence there. Throws tpf::Error
/// when the sizes disagree.
TcnSequence training_sequence(const EstimatorTrace& trace, int joint = -1);

/// Per-sample loss weights that emphasise the regimes the nominal model gets most wrong, from the
/// one regime labelling of the offline tools (label_regimes on each joint's t, q̇ with `regimes`;
/// no compensated residual exists yet, so a static-to-kinetic window lasts
/// regimes.fallback_transition_s after |q̇| crosses regimes.static_velocity):
///   w = static_to_kinetic_weight (StaticToKinetic), static_weight (Static), 1 otherwise.
/// T × N, or T × 1 for one joint (same columns as training_sequence). Break-away samples are ~3 %
/// of an excitation log; without a weight the loss hardly sees them.
Eigen::MatrixXd regime_weights(const EstimatorTrace& trace, int joint, double static_weight,
                               double static_to_kinetic_weight, const RegimeOptions& regimes = {});

/// Multiplies output o of both heads (weights and bias) by scale[o]: the network then predicts
/// scale[o] times its output o (the heads are linear, so this is exact; `tpf upgrade` converts
/// the outputs of old weight files from mA to N·m with it).
void scale_tcn_outputs(TcnParameters& parameters, const Eigen::VectorXd& scale);

/// Removes input channel c of `parameters` for every c in `channels`: zeroes its columns in block
/// 0 (every tap and the projection) and sets its normalisation to mean 0, std 1. The network's
/// output then does not depend on that input at all. Exact on data where the channel was held at
/// 0 (what train_compensator trains a masked channel on). Throws tpf::Error for a channel out of
/// range.
void mask_tcn_inputs(TcnParameters& parameters, const std::vector<int>& channels);

}  // namespace tpf::offline
