// The compensator scored against the nominal model on data it was not trained on: the held-out
// gain per joint and regime that the weight files carry and the run-time gate reads.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "offline/compensator_training/train_compensator.hpp"
#include "offline/regimes/regime.hpp"
#include "offline/replay/estimator_trace.hpp"

namespace tpf::offline {

/// Per regime (TcnWeightFile::kHeldOutRegimes: static, static-to-kinetic, moving) and joint.
struct HeldOutScore {
  std::array<Eigen::VectorXd, 3> nominal_rmse, compensated_rmse;  ///< [N·m]
  std::array<Eigen::VectorXd, 3> gain;  ///< 1 − compensated/nominal; NaN: too few rows
  std::array<Eigen::VectorXi, 3> rows;
};

/// Scores the traces of held-out logs replayed with the compensator (trace.compensation): per
/// joint and regime (label_regimes on t, q̇ with `regimes`, the static-to-kinetic window from both
/// residuals), the RMSE of the nominal residual τ_res and of τ_res − τ_TCN over the rows of that
/// regime, and the gain 1 − compensated/nominal; NaN where a regime holds fewer than `min_rows`
/// rows or the nominal RMSE is 0.
HeldOutScore score_held_out(const std::vector<EstimatorTrace>& traces,
                            const RegimeOptions& regimes = {}, int min_rows = 20);

/// Writes the score into the weight files of `training` (per joint: file j gets joint j's gains;
/// all joints: the one file, output j = joint j).
void set_held_out_gains(CompensatorTraining& training, const HeldOutScore& score);

/// One line per joint: its three gains, and whether the gate with `min_gain` keeps its network.
std::vector<std::string> describe_held_out(const HeldOutScore& score, double min_gain);

}  // namespace tpf::offline
