// Pass 3 of diagnose: forward selection over the candidate library, on Gram matrices (any joint
// count). Each round tries every candidate on the model so far, scores it on the held-out blocks,
// and adds the best one that passes (held-out gain, BIC, standard errors), named alone or as
// "ambiguous between" the candidates (or the declared group) its columns cannot be told from.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "offline/diagnose/diagnose.hpp"
#include "offline/fit/gram_fit.hpp"

namespace tpf::offline {

/// The held-out residual table of θ (per joint: static, static-to-kinetic, moving, all).
RegimeTable heldout_table(const DesignGrams& grams, const Eigen::VectorXd& theta);

/// Σ_j w_j of the training Grams of the regimes `selection` fits on: [φ; y; 1] over every
/// joint's rows.
Eigen::MatrixXd training_gram(const DesignGrams& grams, const FitSelection& selection);

/// Held-out SSE and sample count over moving samples (static-to-kinetic and moving) of `joint`,
/// or of every joint weighted by w when joint < 0. At rest the effort holds whatever friction the
/// motion left (memory), which would only add history noise to the score.
std::pair<double, double> heldout_sse(const RegimeTable& table, int joint,
                                      const Eigen::VectorXd& w);

/// Another group of files of a several-file log held out instead of the selection's (its Grams
/// with those files' samples in the held-out split): a candidate's gain must transfer to it.
struct TransferFold {
  std::string file;  ///< the held-out files' names
  DesignGrams grams;
};

/// A held-out group (the selection's or a transfer fold's) scored only where the fit did not go:
/// the same training rows, the held-out rows of joint j kept where q_j lies outside the range
/// of q_j over the training rows. An effect that extrapolates in q must lower the error there.
struct OutsideFold {
  std::string file;  ///< the held-out files' names
  DesignGrams grams;
};

struct EffectSelection {
  std::vector<CandidateTrial> trials;
  std::vector<int> selected;  ///< indices into the groups, in selection order
  std::vector<Claim> claims;  ///< one per selected group
  RegimeTable before, after;  ///< held-out, declared / selected (with the friction held at rest)
  Eigen::VectorXd theta_declared;  ///< the declared columns fitted on motion (identify's fit)
  Eigen::VectorXd theta_before;    ///< … plus the friction held at rest, fitted at rest
  Eigen::VectorXd theta_selected;  ///< declared + selected, plus the held friction
  /// What the parameter file gets: declared + the written effects, refitted without those not
  /// written (so that the declared parameters are not the ones fitted beside them), plus the
  /// held friction.
  Eigen::VectorXd theta_written;
  /// theta_written's columns refitted on every row, held-out ones included (and the held
  /// friction with them), with the final fit's prior: what the parameter file gets once the
  /// selection is judged.
  Eigen::VectorXd theta_final;
};

/// Selection on `grams` over `groups` (declared ones first), starting from `theta_declared` (the
/// declared columns' fit on `selection`'s rows: identify's) and fitting on `selection`'s rows
/// with its joint weights and prior; theta_final on `every`'s (every row, the written model's
/// prior strength). Standard errors inflated per joint by `variance_inflation`. A candidate
/// must also lower the held-out error of every fold in `transfer` (none for a one-file log), and
/// one that extrapolates in q that of every fold in `outside` with samples outside the range.
EffectSelection select_effects(const DesignGrams& grams, const std::vector<TransferFold>& transfer,
                               const std::vector<OutsideFold>& outside,
                               const std::vector<FeatureGroup>& groups,
                               const std::vector<int>& declared_columns,
                               const Eigen::VectorXd& theta_declared, const FitSelection& selection,
                               const FitSelection& every, const Eigen::VectorXd& variance_inflation,
                               const DiagnoseOptions& options);

}  // namespace tpf::offline
