#include "offline/diagnose/effect_selection.hpp"

#include <algorithm>
#include <cmath>

#include "offline/diagnose/column_geometry.hpp"

namespace tpf::offline {

RegimeTable heldout_table(const DesignGrams& grams, const Eigen::VectorXd& theta) {
  RegimeTable table(grams.joints);
  for (int j = 0; j < grams.joints; ++j)
    for (int r = 0; r < DesignGrams::kRegimes; ++r) {
      table[j][r] = residual_sums(grams, theta, j, r, 1);
      table[j][3] += table[j][r];
    }
  return table;
}

std::pair<double, double> heldout_sse(const RegimeTable& t, int joint, const Eigen::VectorXd& w) {
  double sse = 0, count = 0;
  for (int j = 0; j < static_cast<int>(t.size()); ++j)
    if (joint < 0 || joint == j)
      for (int r = 1; r < DesignGrams::kRegimes; ++r) {
        sse += (joint < 0 ? w[j] : 1.0) * t[j][r].sum_squares;
        count += t[j][r].count;
      }
  return {sse, count};
}

namespace {

/// heldout_sse of the joints group g acts on: its joint's, its pair's (weighted) or every
/// joint's (weighted).
std::pair<double, double> group_sse(const RegimeTable& t, const FeatureGroup& g,
                                    const Eigen::VectorXd& w) {
  if (g.joints.empty()) return heldout_sse(t, g.joint, w);
  double sse = 0, count = 0;
  for (int j : g.joints) {
    const auto [joint_sse, joint_count] = heldout_sse(t, j, w);
    sse += w[j] * joint_sse;
    count += joint_count;
  }
  return {sse, count};
}

}  // namespace

Eigen::MatrixXd training_gram(const DesignGrams& grams, const FitSelection& selection) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(grams.features + 2, grams.features + 2);
  for (int j = 0; j < grams.joints; ++j)
    for (int r = 0; r < DesignGrams::kRegimes; ++r)
      if (selection.regimes[r])
        A +=
            (selection.joint_weights.size() ? selection.joint_weights[j] : 1.0) * grams.at(j, r, 0);
  return A;
}

namespace {

/// The state of a forward selection: the model so far and the library it draws from.
class ForwardSelection {
 public:
  ForwardSelection(const DesignGrams& grams, const std::vector<TransferFold>& transfer,
                   const std::vector<OutsideFold>& outside, const std::vector<FeatureGroup>& groups,
                   const std::vector<int>& declared_columns, const Eigen::VectorXd& theta_declared,
                   const FitSelection& selection, const FitSelection& every,
                   const Eigen::VectorXd& inflation, const DiagnoseOptions& options)
      : grams_(grams),
        transfer_(transfer),
        outside_(outside),
        groups_(groups),
        declared_columns_(declared_columns),
        selection_(selection),
        every_(every),
        inflation_(inflation),
        options_(options),
        A_(training_gram(grams, selection)),
        used_(groups.size(), false),
        columns_(declared_columns),
        theta_(theta_declared) {
    for (std::size_t g = 0; g < groups.size(); ++g)
      if (groups[g].declared) in_model_.push_back(static_cast<int>(g));
    declared_fitted_.assign(static_cast<std::size_t>(grams.features), 0);
    for (int c : declared_columns)
      declared_fitted_[static_cast<std::size_t>(c)] = 1;
  }

  EffectSelection run() {
    EffectSelection out;
    out.theta_declared = theta_;
    out.theta_before = with_held_friction(theta_, columns_);
    out.before = heldout_table(grams_, out.theta_before);
    for (int round = 1; round <= options_.max_effects; ++round)
      if (!select_one(round, out)) break;
    out.theta_selected = with_held_friction(theta_, columns_);
    out.after = heldout_table(grams_, out.theta_selected);
    const std::vector<int> written = written_columns(out);
    // Nothing written: the declared model as given, not refitted.
    out.theta_written = written.size() == declared_columns_.size()
                            ? out.theta_before
                            : with_held_friction(fit_columns(grams_, written, selection_), written);
    out.theta_final = with_held_friction(fit_columns(grams_, written, every_), written, every_);
    return out;
  }

 private:
  /// One round: every candidate tried on the model so far; the best that passes joins it.
  bool select_one(int round, EffectSelection& out) {
    const std::vector<int> model = model_columns(-1);
    std::vector<int> eligible, untransferred;
    std::vector<double> gain(groups_.size(), 0.0);
    std::vector<std::size_t> trial_of(groups_.size(), 0);
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      if (groups_[g].declared || used_[g] || energetic(groups_[g]).empty()) continue;
      const CandidateTrial trial = try_candidate(static_cast<int>(g), round, model);
      gain[g] = trial.improvement;
      trial_of[g] = out.trials.size();
      out.trials.push_back(trial);
      if (trial.fails_transfer(options_)) untransferred.push_back(static_cast<int>(g));
      if (trial.passes_heldout(options_) && !trial.fails_transfer(options_) &&
          !trial.fails_outside(options_))
        eligible.push_back(static_cast<int>(g));
    }
    drop_stand_ins(eligible, untransferred, gain, model, [&](int g) -> CandidateTrial& {
      return out.trials[trial_of[static_cast<std::size_t>(g)]];
    });
    if (eligible.empty()) return false;
    const int best = best_candidate(eligible, gain);
    Claim claim = name_claim(best, eligible, gain, model);
    used_[best] = true;
    in_model_.push_back(best);
    out.selected.push_back(best);
    for (CandidateTrial& t : out.trials) {
      if (t.round != round || t.title != groups_[best].title) continue;
      t.selected = true;
      if (std::isfinite(t.model_improvement) && claim.scored_joints.empty()) {
        claim.beside_improvement = claim.improvements[0];  // the claim gives what is written
        claim.improvements[0] = t.model_improvement;
      }
    }
    columns_.insert(columns_.end(), groups_[best].columns.begin(), groups_[best].columns.end());
    theta_ = fit_columns(grams_, columns_, selection_);
    add_coefficients(best, claim);
    claim.written = writable(claim);
    out.claims.push_back(std::move(claim));
    return true;
  }

  /// Takes out of `eligible` each candidate that stands in for a stronger one of its joint that
  /// failed the transfer test: beside the failed one's columns it removes less than
  /// min_improvement, so its gain is the residual the failed candidate explained on this split,
  /// which does not hold on another file. Its trial records which one it stands in for.
  template <typename TrialOf>
  void drop_stand_ins(std::vector<int>& eligible, const std::vector<int>& untransferred,
                      const std::vector<double>& gain, const std::vector<int>& model,
                      TrialOf&& trial_of) const {
    const auto stands_in = [&](int g) {
      for (int f : untransferred) {
        if (gain[f] <= gain[g] || !same_residual(groups_[f], groups_[g])) continue;
        const double beside = gain_beside(g, f, model);
        if (beside >= options_.min_improvement) continue;
        CandidateTrial& t = trial_of(g);
        t.stand_in_for = groups_[f].title;
        t.beside_failed_improvement = beside;
        return true;
      }
      return false;
    };
    eligible.erase(std::remove_if(eligible.begin(), eligible.end(), stands_in), eligible.end());
  }

  /// Two groups that act on a joint in common (an effect of every joint acts on all).
  bool same_residual(const FeatureGroup& a, const FeatureGroup& b) const {
    for (int j = 0; j < grams_.joints; ++j)
      if (acts_on(a, j) && acts_on(b, j)) return true;
    return false;
  }

  /// Held-out gain of candidate g on top of its reference model and candidate f's columns, on
  /// g's joints.
  double gain_beside(int g, int f, const std::vector<int>& model) const {
    std::vector<int> without = reference_for(groups_[g], model).first;
    for (int c : energetic(groups_[f]))
      if (std::find(without.begin(), without.end(), c) == without.end()) without.push_back(c);
    std::vector<int> with = without;
    for (int c : energetic(groups_[g]))
      if (std::find(with.begin(), with.end(), c) == with.end()) with.push_back(c);
    return fold_improvement(grams_, without, with, groups_[g]);
  }

  /// Candidate g on top of the model: held-out gain and BIC, Wald distance from zero, share of
  /// its columns outside the model.
  CandidateTrial try_candidate(int g, int round, const std::vector<int>& model) const {
    const FeatureGroup& group = groups_[g];
    const std::vector<int> own = energetic(group);
    const auto [reference, reference_model] = reference_for(group, model);
    std::vector<int> trial_columns = reference;
    trial_columns.insert(trial_columns.end(), own.begin(), own.end());
    const Eigen::VectorXd trial_theta = fit_columns(grams_, trial_columns, selection_);
    const RegimeTable now = heldout_table(grams_, reference.size() == columns_.size()
                                                      ? theta_
                                                      : fit_columns(grams_, reference, selection_));
    const RegimeTable with = heldout_table(grams_, trial_theta);
    const auto [sse0, n] = group_sse(now, group, selection_.joint_weights);
    const auto [sse1, n1] = group_sse(with, group, selection_.joint_weights);
    CandidateTrial trial;
    trial.key = group.key;
    trial.title = group.title;
    trial.joint = group.joint;
    trial.round = round;
    trial.improvement = sse0 > 0 ? 1.0 - sse1 / sse0 : 0.0;
    for (int c : group.dissipative)
      trial.negative_friction = trial.negative_friction || trial_theta[group.columns[c]] < 0.0;
    if (group.joints.size() > 1)
      for (int j : group.joints) {
        const double joint_sse0 = heldout_sse(now, j, selection_.joint_weights).first;
        const double joint_sse1 = heldout_sse(with, j, selection_.joint_weights).first;
        const double gain = joint_sse0 > 0 ? 1.0 - joint_sse1 / joint_sse0 : 0.0;
        if (!(gain >= trial.weakest_joint_improvement)) trial.weakest_joint_improvement = gain;
      }
    trial.bic_change = n * std::log(std::max(sse1, 1e-300) / std::max(sse0, 1e-300)) +
                       static_cast<double>(group.columns.size()) * std::log(std::max(n, 2.0));
    const double sigma2 = residual_variance(trial_theta, trial_columns.size(), group.joint);
    const Eigen::MatrixXd S = projected_gram(A_, reference_model, own);
    Eigen::VectorXd th(own.size());
    for (std::size_t i = 0; i < own.size(); ++i)
      th[static_cast<Eigen::Index>(i)] = trial_theta[own[i]];
    trial.wald = std::sqrt(std::max(th.dot(S * th), 0.0) / std::max(sigma2, 1e-300));
    trial.distinct_share = distinct_share(A_, reference_model, own);
    if (reference.size() != columns_.size()) {
      std::vector<int> alone = columns_;
      alone.insert(alone.end(), own.begin(), own.end());
      const auto [sse_model, n_model] =
          group_sse(heldout_table(grams_, theta_), group, selection_.joint_weights);
      const auto [sse_alone, n_alone] =
          group_sse(heldout_table(grams_, fit_columns(grams_, alone, selection_)), group,
                    selection_.joint_weights);
      trial.model_improvement = sse_model > 0 ? 1.0 - sse_alone / sse_model : 0.0;
    }
    for (const TransferFold& fold : transfer_) {
      const double gain = fold_improvement(fold.grams, reference, trial_columns, group);
      if (!(gain >= trial.transfer_improvement)) {
        trial.transfer_improvement = gain;
        trial.transfer_file = fold.file;
      }
    }
    trial.extrapolates = group.extrapolates_in_q && group.joint >= 0;
    if (trial.extrapolates)
      for (const OutsideFold& fold : outside_) {
        const double samples = moving_heldout_count(fold.grams, group.joint);
        if (samples <= 0) continue;  // the group never leaves the range: not a test
        const double gain = fold_improvement(fold.grams, reference, trial_columns, group);
        if (!(gain >= trial.outside_improvement)) {
          trial.outside_improvement = gain;
          trial.outside_samples = samples;
          trial.outside_file = fold.file;
        }
      }
    return trial;
  }

  /// The model a candidate is judged on top of (its columns, and the live ones of them): a
  /// periodic effect must explain what an offset and a slope of its joint cannot (over a short
  /// range a sine is one or the other).
  std::pair<std::vector<int>, std::vector<int>> reference_for(const FeatureGroup& group,
                                                              const std::vector<int>& model) const {
    std::vector<int> reference = columns_;
    std::vector<int> reference_model = model;
    for (const std::string& beside : group.judged_beside)
      for (const FeatureGroup& other : groups_)
        if (other.joint == group.joint && other.key == beside)
          for (int c : other.columns)
            if (std::find(reference.begin(), reference.end(), c) == reference.end()) {
              reference.push_back(c);
              if (alive(c)) reference_model.push_back(c);
            }
    return {reference, reference_model};
  }

  /// Held-out gain of candidate g on top of the model, on the weighted moving SSE of `joints`:
  /// candidates of different joints scored alike.
  double gain_on(int g, const std::vector<int>& joints, const std::vector<int>& model) const {
    const std::vector<int> reference = reference_for(groups_[g], model).first;
    std::vector<int> with = reference;
    for (int c : energetic(groups_[g]))
      with.push_back(c);
    const RegimeTable t0 = heldout_table(grams_, fit_columns(grams_, reference, selection_));
    const RegimeTable t1 = heldout_table(grams_, fit_columns(grams_, with, selection_));
    double sse0 = 0, sse1 = 0;
    for (int j : joints) {
      sse0 += selection_.joint_weights[j] * heldout_sse(t0, j, selection_.joint_weights).first;
      sse1 += selection_.joint_weights[j] * heldout_sse(t1, j, selection_.joint_weights).first;
    }
    return sse0 > 0 ? 1.0 - sse1 / sse0 : 0.0;
  }

  /// Held-out samples in motion of `joint` in `fold`.
  static double moving_heldout_count(const DesignGrams& fold, int joint) {
    double n = 0;
    for (int r = 1; r < DesignGrams::kRegimes; ++r)
      n += fold.at(joint, r, 1)(fold.features + 1, fold.features + 1);
    return n;
  }

  /// Fraction of a fold's held-out SSE (on `joint`, or every joint) that `with` removes from
  /// `without`, both fitted on the fold's training rows.
  double fold_improvement(const DesignGrams& fold, const std::vector<int>& without,
                          const std::vector<int>& with, const FeatureGroup& group) const {
    const auto [sse0, n0] = group_sse(heldout_table(fold, fit_columns(fold, without, selection_)),
                                      group, selection_.joint_weights);
    const auto [sse1, n1] = group_sse(heldout_table(fold, fit_columns(fold, with, selection_)),
                                      group, selection_.joint_weights);
    return sse0 > 0 ? 1.0 - sse1 / sse0 : 0.0;
  }

  /// The largest gain; an effect of every joint (one shared delay) is preferred to the same effect
  /// on one joint when both pass: the per-joint one would leave the others for spurious
  /// companions.
  int best_candidate(const std::vector<int>& eligible, const std::vector<double>& gain) const {
    int best = eligible.front();
    for (int g : eligible)
      if (gain[g] > gain[best]) best = g;
    for (int g : eligible)
      if (groups_[g].key == groups_[best].key && groups_[g].joint == -1 && groups_[best].joint >= 0)
        best = g;
    return best;
  }

  /// The claim for `best`: alone, or ambiguous with the eligible candidates of its joint whose
  /// parts outside the model are nearly collinear with its own, with the families it is judged
  /// beside when it cannot be told from them on this log (FeatureGroup::indistinct_from_beside),
  /// with the candidates of other joints that are (cross_joint_alternatives), and with the model
  /// group whose removal frees it most when the model's own columns nearly span it.
  Claim name_claim(int best, const std::vector<int>& eligible, const std::vector<double>& gain,
                   const std::vector<int>& model) const {
    Claim claim;
    claim.groups.push_back(best);
    claim.improvements.push_back(gain[best]);
    const std::vector<int> own = energetic(groups_[best]);
    for (int g : eligible) {
      const FeatureGroup& other = groups_[g];
      if (g == best) continue;
      if (other.joint >= 0 && groups_[best].joint >= 0 && other.joint != groups_[best].joint)
        continue;
      if (other.key == groups_[best].key) continue;  // per-joint vs every-joint of one effect
      if (shared_share(A_, model, own, energetic(other)) >= options_.max_shared_share) {
        claim.groups.push_back(g);
        claim.improvements.push_back(gain[g]);
      }
    }
    if (groups_[best].indistinct_from_beside) add_beside(best, gain, claim);
    add_cross_joint_alternatives(best, eligible, model, claim);
    claim.distinct_share = distinct_share(A_, model, own);
    if (claim.distinct_share < options_.min_distinct_share) {
      int partner = -1;
      double freed = claim.distinct_share;
      for (int g : in_model_) {
        const double share = distinct_share(A_, model_columns(g), own);
        if (share > freed) {
          freed = share;
          partner = g;
        }
      }
      if (partner >= 0) {
        claim.groups.push_back(partner);
        claim.improvements.push_back(std::nan(""));
      }
    }
    return claim;
  }

  /// The families of best's joint it is judged beside, each with its gain this round (NaN: in the
  /// model already).
  void add_beside(int best, const std::vector<double>& gain, Claim& claim) const {
    const FeatureGroup& b = groups_[best];
    for (const std::string& key : b.judged_beside)
      for (std::size_t g = 0; g < groups_.size(); ++g) {
        const int index = static_cast<int>(g);
        if (groups_[g].joint != b.joint || groups_[g].key != key ||
            std::find(claim.groups.begin(), claim.groups.end(), index) != claim.groups.end())
          continue;
        claim.groups.push_back(index);
        claim.improvements.push_back(used_[g] || groups_[g].declared ? std::nan("") : gain[g]);
      }
  }

  /// A candidate of another joint whose part outside the model is nearly collinear with best's
  /// (through the rigid body: with identified armatures, coupling [0; q̈_1] on joint 2 is
  /// −[q̈_2; 0] on joint 1) and that explains the same residual: eligible itself, or removing
  /// cross_joint_gain_ratio of best's gain, both on the weighted held-out SSE of the two joints.
  /// Then every alternative's gain is given on the joints of the claim (a per-joint gain would
  /// score each on its own joint only, where its twin's term does not show).
  void add_cross_joint_alternatives(int best, const std::vector<int>& eligible,
                                    const std::vector<int>& model, Claim& claim) const {
    const FeatureGroup& b = groups_[best];
    if (b.joint < 0) return;
    const std::vector<int> own = energetic(b);
    std::vector<int> joints{b.joint};
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      const FeatureGroup& other = groups_[g];
      if (other.declared || used_[g] || other.joint < 0 || other.joint == b.joint) continue;
      const std::vector<int> theirs = energetic(other);
      if (theirs.empty() || shared_share(A_, model, own, theirs) < options_.max_shared_share)
        continue;
      const bool is_eligible =
          std::find(eligible.begin(), eligible.end(), static_cast<int>(g)) != eligible.end();
      const std::vector<int> pair{b.joint, other.joint};
      if (!is_eligible && gain_on(static_cast<int>(g), pair, model) <
                              options_.cross_joint_gain_ratio * gain_on(best, pair, model))
        continue;
      claim.groups.push_back(static_cast<int>(g));
      claim.improvements.push_back(0.0);
      if (std::find(joints.begin(), joints.end(), other.joint) == joints.end())
        joints.push_back(other.joint);
    }
    if (joints.size() == 1) return;
    std::sort(joints.begin(), joints.end());
    claim.scored_joints = joints;
    for (std::size_t i = 0; i < claim.groups.size(); ++i)
      claim.improvements[i] = gain_on(claim.groups[i], joints, model);
  }

  /// The coefficients of `best` on the model it joined, with their standard errors.
  void add_coefficients(int best, Claim& claim) const {
    const std::vector<int> own = energetic(groups_[best]);
    const Eigen::MatrixXd S = projected_gram(A_, model_columns(best), own);
    const double sigma2 = residual_variance(theta_, columns_.size(), groups_[best].joint);
    const Eigen::MatrixXd cov = sigma2 * symmetric_power(S, -1.0);
    for (std::size_t i = 0; i < own.size(); ++i) {
      claim.coefficients.push_back(theta_[own[i]]);
      claim.standard_errors.push_back(std::sqrt(std::max(cov(i, i), 0.0)));
    }
  }

  /// Written only when the run time evaluates it and its coefficients mean something: an
  /// ambiguous claim — one that cannot be told from the declared model (a spring beside
  /// gravity's mx) or from another candidate (an offset beside direction-asymmetric friction
  /// under one-directional motion, which predict differently once the joint reverses) — is
  /// reported, not written.
  bool writable(const Claim& claim) const {
    const WrittenTo to = groups_[claim.groups[0]].written_to;
    return to != WrittenTo::kNothing && to != WrittenTo::kRobotFile && !claim.ambiguous();
  }

  std::vector<int> written_columns(const EffectSelection& out) const {
    std::vector<int> written = declared_columns_;
    for (std::size_t e = 0; e < out.claims.size(); ++e)
      if (out.claims[e].written)
        for (int c : energetic(groups_[out.selected[e]]))
          written.push_back(c);
    return written;
  }

  /// σ̂² = weighted training SSE/(n − p), inflated for the residual's autocorrelation on `joint`
  /// (the largest inflation for an effect of every joint).
  double residual_variance(const Eigen::VectorXd& theta, std::size_t parameters, int joint) const {
    double sse = 0, count = 0;
    for (int j = 0; j < grams_.joints; ++j)
      for (int r = 0; r < DesignGrams::kRegimes; ++r)
        if (selection_.regimes[r]) {
          const ResidualSums sums = residual_sums(grams_, theta, j, r, 0);
          sse += selection_.joint_weights[j] * sums.sum_squares;
          count += sums.count;
        }
    return sse / std::max(count - static_cast<double>(parameters), 1.0) *
           (joint >= 0 ? inflation_[joint] : inflation_.maxCoeff());
  }

  /// The friction held at rest (last direction of motion × level, and × |G| once load-dependent
  /// friction is in the model) fitted on the static training samples on top of the model fitted
  /// on motion, which it leaves unchanged.
  Eigen::VectorXd with_held_friction(const Eigen::VectorXd& moving_theta,
                                     const std::vector<int>& used) const {
    return with_held_friction(moving_theta, used, selection_);
  }
  Eigen::VectorXd with_held_friction(const Eigen::VectorXd& moving_theta,
                                     const std::vector<int>& used, const FitSelection& rows) const {
    FitSelection at_rest = rows;
    at_rest.regimes = {true, false, false};
    std::vector<int> held;
    for (const FeatureGroup& g : groups_)
      if (g.held_column >= 0 &&
          std::find(used.begin(), used.end(), g.columns[g.held_column]) != used.end())
        held.push_back(g.columns[g.held_column]);
    return refit_columns(grams_, held, moving_theta, at_rest);
  }

  /// A column with (numerically) nothing in it on the training rows, e.g. |G_k| of a joint whose
  /// axis is vertical (rounding noise of 1e-16), is left out: its coefficient would be anything.
  bool alive(int col) const {
    const int P = grams_.features;
    return A_(col, col) > 1e-20 * A_(P + 1, P + 1);
  }
  /// The live columns of the groups in the model so far, but `except`.
  std::vector<int> model_columns(int except) const {
    std::vector<int> c;
    for (int g : in_model_)
      if (g != except)
        for (int col : groups_[g].columns)
          if (alive(col) &&
              (!groups_[g].declared || declared_fitted_[static_cast<std::size_t>(col)]))
            c.push_back(col);
    return c;
  }
  std::vector<int> energetic(const FeatureGroup& group) const {
    std::vector<int> c;
    for (int col : group.columns)
      if (alive(col)) c.push_back(col);
    return c;
  }

  const DesignGrams& grams_;
  const std::vector<TransferFold>& transfer_;
  const std::vector<OutsideFold>& outside_;
  const std::vector<FeatureGroup>& groups_;
  const std::vector<int>& declared_columns_;
  const FitSelection& selection_;
  const FitSelection& every_;  ///< the final refit's rows (every one) and prior
  const Eigen::VectorXd& inflation_;
  const DiagnoseOptions& options_;
  const Eigen::MatrixXd A_;  ///< the weighted training Gram of the selected regimes
  std::vector<bool> used_;
  std::vector<int> in_model_;  ///< groups in the model (declared first), for naming partners
  /// Per feature: a declared column the declared fit uses (a coupled model leaves out its
  /// coupled motors' joint friction and its uncoupled motors' motor friction).
  std::vector<char> declared_fitted_;
  std::vector<int> columns_;  ///< the model's columns
  Eigen::VectorXd theta_;     ///< the model fitted on motion
};

}  // namespace

EffectSelection select_effects(const DesignGrams& grams, const std::vector<TransferFold>& transfer,
                               const std::vector<OutsideFold>& outside,
                               const std::vector<FeatureGroup>& groups,
                               const std::vector<int>& declared_columns,
                               const Eigen::VectorXd& theta_declared, const FitSelection& selection,
                               const FitSelection& every, const Eigen::VectorXd& variance_inflation,
                               const DiagnoseOptions& options) {
  return ForwardSelection(grams, transfer, outside, groups, declared_columns, theta_declared,
                          selection, every, variance_inflation, options)
      .run();
}

}  // namespace tpf::offline
