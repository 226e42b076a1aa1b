#include "offline/identify/inertia_prior.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "offline/effects/effect_columns.hpp"
#include "offline/report/text_format.hpp"
#include "tpf/dynamics/regressor.hpp"

namespace tpf::offline {

MassMatrixProbe::MassMatrixProbe(const NominalModelX& like) : joints_(like.model.joint_count()) {
  const int n = joints_;
  DataX data(like.model);
  Eigen::MatrixXd Y0, Yi;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  for (const Eigen::VectorXd& q : mass_check_poses(like.model)) {
    compute_regressor(like.model, data, q, zero, zero, Y0);
    Eigen::MatrixXd& map = maps_.emplace_back(n * n, like.base_count);
    for (int i = 0; i < n; ++i) {
      compute_regressor(like.model, data, q, zero, Eigen::VectorXd::Unit(n, i), Yi);
      for (int c = 0; c < like.base_count; ++c)
        map.col(c).segment(n * i, n) = Yi.col(like.base_columns[c]) - Y0.col(like.base_columns[c]);
    }
  }
}

bool MassMatrixProbe::above(const NominalModelX& nominal, double floor) const {
  const int n = joints_;
  // Sized once for every pose.
  Eigen::VectorXd m(n * n);
  Eigen::MatrixXd shifted(n, n);
  Eigen::LLT<Eigen::MatrixXd> factor(n);
  for (const Eigen::MatrixXd& map : maps_) {
    m.noalias() = map * nominal.base_values.head(nominal.base_count);
    const Eigen::Map<const Eigen::MatrixXd> M(m.data(), n, n);
    shifted = 0.5 * (M + M.transpose()) - floor * Eigen::MatrixXd::Identity(n, n);
    if (factor.compute(shifted).info() != Eigen::Success) return false;
  }
  return true;
}

double MassMatrixProbe::min_eigenvalue(const NominalModelX& nominal) const {
  double smallest = std::numeric_limits<double>::infinity();
  const int n = joints_;
  // Sized once for every pose.
  Eigen::VectorXd m(n * n);
  Eigen::MatrixXd sym(n, n);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(n);
  for (const Eigen::MatrixXd& map : maps_) {
    m.noalias() = map * nominal.base_values.head(nominal.base_count);
    const Eigen::Map<const Eigen::MatrixXd> M(m.data(), n, n);
    sym = 0.5 * (M + M.transpose());
    smallest =
        std::min(smallest, solver.compute(sym, Eigen::EigenvaluesOnly).eigenvalues().minCoeff());
  }
  return smallest;
}

ColumnPrior robot_file_prior(const ModelX& model, const EffectDesign& design,
                             const BaseParameters& base) {
  const int n = model.joint_count();
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd values =
      base.project(dynamic_parameters(model, zero, zero).head(11 * n).eval());
  ColumnPrior prior;
  prior.mean = Eigen::VectorXd::Zero(design.features());
  for (const FeatureGroup& g : design.groups())
    if (g.key == RigidBodyColumns::key)
      for (int i = 0; i < base.size(); ++i) {
        prior.mean[g.columns[i]] = values[i];
        prior.columns.push_back(g.columns[i]);
      }
  return prior;
}

RobotFileInertiaPrior robot_file_inertia_prior(const ModelX& model, const EffectDesign& design,
                                               const BaseParameters& base) {
  RobotFileInertiaPrior out;
  out.prior = robot_file_prior(model, design, base);
  const NominalModelX own = linear_nominal(model, design, base, out.prior.mean).nominal;
  out.floor = 0.1 * min_mass_eigenvalue(own);
  if (out.floor > 0) out.probe = MassMatrixProbe(own);
  return out;
}

std::vector<double> inertia_prior_ladder() {
  return {0, 1e-4, 1e-3, 1e-2, 1e-1, 1, 10, 100};
}

namespace {

/// √(Σ_j w_j SSE_j / Σ_j n_j) of θ over the held-out rows of `selection`'s regimes (NaN: none).
double weighted_heldout_error(const DesignGrams& grams, const Eigen::VectorXd& theta,
                              const FitSelection& selection) {
  double sum = 0, count = 0;
  for (int j = 0; j < grams.joints; ++j)
    for (int r = 0; r < DesignGrams::kRegimes; ++r)
      if (selection.regimes[r]) {
        const ResidualSums sums = residual_sums(grams, theta, j, r, 1);
        sum +=
            (selection.joint_weights.size() ? selection.joint_weights[j] : 1.0) * sums.sum_squares;
        count += sums.count;
      }
  return count > 0 ? std::sqrt(sum / count) : std::numeric_limits<double>::quiet_NaN();
}

/// The fits of one design and row selection at any strength of one prior.
struct PriorFits {
  const ModelX& model;
  const EffectDesign& design;
  const BaseParameters& base;
  const DesignGrams& grams;
  const std::vector<int>& columns;
  FitSelection selection;

  Eigen::VectorXd theta(const RobotFileInertiaPrior* prior, double strength) {
    if (prior) selection.prior = prior->prior;
    selection.prior.strength = strength;
    return fit_columns(grams, columns, selection);
  }
  LinearNominal nominal(const Eigen::VectorXd& theta) const {
    return linear_nominal(model, design, base, theta);
  }
};

/// The smallest strength in [1e-8, 100] whose fit's M(q) is above the floor (bisection on its
/// logarithm, 20 halvings), NaN when even 100 does not lift it.
double smallest_lifting_strength(PriorFits& fits, const RobotFileInertiaPrior& prior) {
  double weak = -8, strong = 2;  // log10 of the strength: below the floor at `weak`
  if (!prior.probe.above(fits.nominal(fits.theta(&prior, std::pow(10.0, strong))).nominal,
                         prior.floor))
    return std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 20; ++k) {
    const double middle = 0.5 * (weak + strong);
    if (prior.probe.above(fits.nominal(fits.theta(&prior, std::pow(10.0, middle))).nominal,
                          prior.floor))
      strong = middle;
    else
      weak = middle;
  }
  return std::pow(10.0, strong);
}

/// Index of the chosen candidate (PriorFit's rule) and why, in a sentence.
std::pair<std::size_t, std::string> chosen_candidate(const std::vector<PriorCandidate>& c) {
  constexpr double kPreferWeaker = 0.01;
  std::vector<std::size_t> pd;
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c[i].positive_definite) pd.push_back(i);
  const bool heldout = std::isfinite(c.front().heldout_error);
  const std::string tried = format_sentence("%.0f", static_cast<double>(c.size()));
  if (!heldout) {
    if (pd.empty())
      return {c.size() - 1, "nothing is held out and no strength of the " + tried +
                                " tried lifts M(q) to the floor: the strongest"};
    return {pd.front(), "nothing is held out: the weakest of the " + tried +
                            " strengths tried that lifts M(q) to the floor"};
  }
  std::vector<std::size_t> pool = pd;
  if (pool.empty())
    for (std::size_t i = 0; i < c.size(); ++i)
      pool.push_back(i);
  std::size_t best = pool.front();
  for (std::size_t i : pool)
    if (c[i].heldout_error < c[best].heldout_error) best = i;
  std::size_t chosen = best;
  for (std::size_t i : pool)  // ascending strength: the first within reach is the weakest
    if (c[i].heldout_error <= (1 + kPreferWeaker) * c[best].heldout_error) {
      chosen = i;
      break;
    }
  std::string why = pd.empty()
                        ? "no strength of the " + tried +
                              " tried lifts M(q) to the floor: the lowest held-out error of all"
                        : format_sentence(
                              "the lowest held-out error among the %.0f of %.0f strengths "
                              "tried that keep M(q) above the floor",
                              static_cast<double>(pd.size()), static_cast<double>(c.size()));
  if (chosen != best)
    why += " (a weaker strength within 1 % of the lowest, " + format_number(c[best].strength, 3) +
           ", is preferred)";
  return {chosen, why};
}

}  // namespace

PriorFit choose_inertia_prior(const ModelX& model, const EffectDesign& design,
                              const BaseParameters& base, const DesignGrams& grams,
                              const std::vector<int>& columns, FitSelection selection,
                              const RobotFileInertiaPrior* prior) {
  PriorFits fits{model, design, base, grams, columns, selection};
  PriorFit out;
  out.fit = fits.nominal(fits.theta(prior, 0));
  if (!prior) return out;
  out.min_eigenvalue_without = min_mass_eigenvalue(out.fit.nominal);
  // A plain fit whose M(q) is above the floor is the data's own: no prior.
  if (!(prior->floor > 0) || out.min_eigenvalue_without >= prior->floor) return out;
  std::vector<double> strengths = inertia_prior_ladder();
  const double lifting = smallest_lifting_strength(fits, *prior);
  if (std::isfinite(lifting)) strengths.push_back(lifting);
  std::sort(strengths.begin(), strengths.end());
  std::vector<LinearNominal> trials;
  for (double strength : strengths) {
    const Eigen::VectorXd theta = fits.theta(prior, strength);
    LinearNominal& trial = trials.emplace_back(fits.nominal(theta));
    const double min_eigenvalue = prior->probe.min_eigenvalue(trial.nominal);
    out.candidates.push_back({strength, weighted_heldout_error(grams, theta, selection),
                              min_eigenvalue, min_eigenvalue > prior->floor});
  }
  const auto [chosen, why] = chosen_candidate(out.candidates);
  out.fit = std::move(trials[chosen]);
  out.strength = out.candidates[chosen].strength;
  out.choice = why;
  return out;
}

PriorFit refit_with_inertia_prior(const ModelX& model, const EffectDesign& design,
                                  const BaseParameters& base, const DesignGrams& grams,
                                  const std::vector<int>& columns, FitSelection selection,
                                  const RobotFileInertiaPrior* prior, const PriorFit& judged) {
  PriorFits fits{model, design, base, grams, columns, selection};
  PriorFit out;
  out.fit = fits.nominal(fits.theta(prior, 0));
  if (!prior) return out;
  out.min_eigenvalue_without = min_mass_eigenvalue(out.fit.nominal);
  if (!(prior->floor > 0)) return out;
  if (judged.candidates.empty()) {  // the judged fit needed none; this one, if it does: the least
    if (out.min_eigenvalue_without >= prior->floor) return out;
    const double lifting = smallest_lifting_strength(fits, *prior);
    out.strength = std::isfinite(lifting) ? lifting : inertia_prior_ladder().back();
    out.fit = fits.nominal(fits.theta(prior, out.strength));
    out.choice =
        "the smallest strength that lifts M(q) to the floor (the fit on the training "
        "rows needed none)";
    return out;
  }
  out.candidates = judged.candidates;
  out.choice = judged.choice;
  out.strength = judged.strength;
  out.fit = fits.nominal(fits.theta(prior, out.strength));
  const bool judged_above =
      std::any_of(judged.candidates.begin(), judged.candidates.end(), [&](const PriorCandidate& c) {
        return c.strength == judged.strength && c.positive_definite;
      });
  // Where no strength lifted the judged fit to the floor, none is looked for here either.
  if (judged_above && !prior->probe.above(out.fit.nominal, prior->floor)) {
    const double lifting = smallest_lifting_strength(fits, *prior);
    if (std::isfinite(lifting) && lifting > out.strength) {
      out.strength = lifting;
      out.fit = fits.nominal(fits.theta(prior, lifting));
      out.choice += "; on every row, the smallest strength above it that lifts M(q) to the floor";
    }
  }
  return out;
}

}  // namespace tpf::offline
