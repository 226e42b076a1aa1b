// Folder fit/: the weighted least-squares fit from accumulated Gram matrices (DesignGrams,
// fit_columns), the AVX kernels that reproduce Eigen's summation order (GramRowBlock,
// ThetaProducts) and the two threading helpers of the offline passes (parallel_halves,
// parallel_jobs). It knows nothing of logs, models or effects (only regimes/' labels).
//
// Least squares from accumulated Gram matrices: one pass over an hour-long log, then any subset
// of columns can be fitted on the training blocks and scored on the held-out blocks for free.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "offline/regimes/regime.hpp"

namespace tpf::offline {

/// Augmented Gram matrices Σ z zᵀ of z = [φ (P features); y; 1] per joint row, regime (static,
/// static-to-kinetic, moving) and split (training, held-out). From one block one gets Σφφᵀ, Σφy,
/// Σy², Σφ, Σy and the count, so that for any θ the residual r = y − φᵀθ has
///   Σr² = θᵀ(Σφφᵀ)θ − 2θᵀΣφy + Σy²,  Σr = Σy − θᵀΣφ.
struct DesignGrams {
  static constexpr int kRegimes = 3;  ///< Regime::Static, StaticToKinetic, Moving
  int joints = 0;
  int features = 0;                     ///< P
  std::vector<Eigen::MatrixXd> blocks;  ///< (P+2)², index (joint·3 + regime)·2 + split

  DesignGrams() = default;
  DesignGrams(int joints, int features);
  Eigen::MatrixXd& at(int joint, int regime, int split) {
    return blocks[(joint * kRegimes + regime) * 2 + split];
  }
  const Eigen::MatrixXd& at(int joint, int regime, int split) const {
    return blocks[(joint * kRegimes + regime) * 2 + split];
  }
  DesignGrams& operator+=(const DesignGrams& other);
};

/// A Gaussian prior on some columns: the fit minimises the weighted sum of squares plus
/// strength · Σ_c s_c·(θ_c − mean_c)² over the prior's columns that it fits, s_c the column's own
/// diagonal Σ_j w_j Σ φ_c² of the selected rows. The strength is relative: 0.01 weighs the prior
/// as 1 % of the data's information on each column; 0 (the default) is no prior.
struct ColumnPrior {
  Eigen::VectorXd mean;      ///< P-vector (only the prior's columns are read)
  std::vector<int> columns;  ///< the columns it holds
  double strength = 0;
};

/// Which rows a fit uses and how joints are weighted.
struct FitSelection {
  std::array<bool, DesignGrams::kRegimes> regimes{true, true, true};
  Eigen::VectorXd joint_weights;  ///< w_j (1/σ_j²); empty = all 1
  /// The held-out rows too: the final fit of a model chosen on held-out data, which the file
  /// gets once nothing is left to judge.
  bool heldout_rows = false;
  ColumnPrior prior;  ///< on the fitted columns that it holds; none by default
};

/// θ over `columns` (others zero) minimising Σ_j w_j Σ_(training rows of j) r² with column
/// equilibration and a complete orthogonal decomposition (rank-deficient sets give the
/// minimum-norm solution). Returns a P-vector.
Eigen::VectorXd fit_columns(const DesignGrams& grams, const std::vector<int>& columns,
                            const FitSelection& selection);

/// θ with `columns` refitted on the residual y − φᵀθ of the selected rows while every other
/// column keeps its value in `theta`: minimises Σ_j w_j Σ (y − φᵀθ_fixed − φ_cᵀθ_c)² over θ_c
/// (same equilibrated, rank-safe solve as fit_columns). Used to fit the friction held at rest
/// on static samples without moving the model fitted on motion.
Eigen::VectorXd refit_columns(const DesignGrams& grams, const std::vector<int>& columns,
                              const Eigen::VectorXd& theta, const FitSelection& selection);

/// Residual sums of θ on one joint, regime and split.
struct ResidualSums {
  double count = 0, sum = 0, sum_squares = 0;
  ResidualSums& operator+=(const ResidualSums& o) {
    count += o.count;
    sum += o.sum;
    sum_squares += o.sum_squares;
    return *this;
  }
  double rmse() const;
  double mean() const;
  double std() const;
};
ResidualSums residual_sums(const DesignGrams& grams, const Eigen::VectorXd& theta, int joint,
                           int regime, int split);

/// Per joint, 1/σ² of θ's residual on the training rows (split 0) while moving, the weights of
/// the weighted fits. A joint that never moves in the log (braked, or left out of the excitation)
/// has no moving rows: its σ is then that of its residual at rest, so that its weight stays
/// finite (one NaN weight turns every fit to NaN). σ is at least 1e-9, and 1 for a joint without
/// rows.
Eigen::VectorXd moving_residual_weights(const DesignGrams& grams, const Eigen::VectorXd& theta);

}  // namespace tpf::offline
