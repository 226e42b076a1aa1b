// TCN training data from estimator traces of contact-free logs.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/train/tcn_trainer.hpp"
#include "offline/training/estimator_trace.hpp"

namespace tpf::offline {

/// One training sequence from the trace of a contact-free log (N joints):
///   inputs   = the compensator inputs the estimator built, x = [q; q̇; q̈; τ̂_fric,s] (T × 4N), or
///              for joint ≥ 0 that joint's four columns [q_j, q̇_j, q̈_j, τ̂_fric,s,j] (T × 4);
///   residual = τ_res / effort_per_newton_metre = (τ_meas − predict_effort(q, q̇, q̈)) [N·m]
///              (T × N, or T × 1 for one joint): the friction the nominal model misses.
/// Rows the estimator skipped stay NaN: the trainer cuts the sequence there. Training in N·m keeps
/// the targets O(1) for Adam; scale_tcn_outputs converts the trained heads back to the effort unit.
/// Throws tpf::Error when the sizes disagree.
TcnSequence training_sequence(const EstimatorTrace& trace,
                              const Eigen::VectorXd& effort_per_newton_metre, int joint = -1);

/// Extra sequences that put weight on break-away: for every static → moving transition of any
/// joint in the trace (|q̇_j| crossing `static_velocity` after a static row), the rows
/// [k₀ − lead − (receptive_field − 1), k₀ − lead + outputs), i.e. exactly one training window of
/// `outputs` supervised steps that starts `lead` rows before the onset. Same columns as
/// training_sequence(trace, scale, joint). Windows that would leave the trace or hold a NaN row
/// are left out. These rows also occur in the plain sequence: the emphasis is a duplication.
std::vector<TcnSequence> onset_sequences(const EstimatorTrace& trace,
                                         const Eigen::VectorXd& effort_per_newton_metre, int joint,
                                         int receptive_field, int outputs, int lead,
                                         double static_velocity = 1e-4);

/// Multiplies output o of both heads (weights and bias) by scale[o]: a network trained on
/// residual/scale then predicts the residual itself (the heads are linear, so this is exact).
void scale_tcn_outputs(TcnParameters& parameters, const Eigen::VectorXd& scale);

}  // namespace tpf::offline
