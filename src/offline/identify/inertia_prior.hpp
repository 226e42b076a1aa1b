// The robot file's inertias as a prior on the identified rigid body: its strength chosen on
// held-out error among those that make M(q) positive definite.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "offline/common/run_time_types.hpp"
#include "offline/fit/gram_fit.hpp"
#include "offline/identify/effect_design.hpp"
#include "offline/identify/identify.hpp"
#include "tpf/dynamics/base_parameters.hpp"

namespace tpf::offline {

/// The robot file's own rigid body as a prior on `design`'s rigid-body columns: their base values
/// β·π of the file's inertias and armature (strength 0: set it to use it).
ColumnPrior robot_file_prior(const ModelX& model, const EffectDesign& design,
                             const BaseParameters& base);

/// M(q) at check_consistency's poses as a linear map of the base values: per pose, column i of
/// M is (Y(q, 0, e_i) − Y(q, 0, 0)).cols(base_columns)·base_values, the regressors computed
/// once, so that each of the bisection's trials costs products instead of (N + 1)·200
/// regressor passes.
class MassMatrixProbe {
 public:
  MassMatrixProbe() = default;  ///< no poses: above() holds
  /// For models with the kinematics and base columns of `like`.
  explicit MassMatrixProbe(const NominalModelX& like);
  /// Whether every eigenvalue of M(q) (symmetrised) of `nominal` exceeds `floor` at every pose: a
  /// Cholesky factor of M − floor·1 exists (the first pose without one ends the test).
  bool above(const NominalModelX& nominal, double floor) const;
  /// The smallest eigenvalue of M(q) (symmetrised) of `nominal` over the poses [kg·m²].
  double min_eigenvalue(const NominalModelX& nominal) const;

 private:
  int joints_ = 0;
  std::vector<Eigen::MatrixXd> maps_;  ///< per pose: (N·N) × base_count, column-major M
};

/// The robot file's inertias as a prior on one design's fits, built once for all of them.
struct RobotFileInertiaPrior {
  ColumnPrior prior;  ///< robot_file_prior (strength 0)
  /// A tenth of the smallest eigenvalue of the robot file's own M(q) [kg·m²]: what the fits'
  /// is lifted to. Not positive where the robot file's own M(q) is not positive definite (a joint
  /// with no inertia of its own or beyond it): no floor to lift the fits' to, no prior.
  double floor = 0;
  MassMatrixProbe probe;  ///< for the design's base columns (where there is a floor)
};

RobotFileInertiaPrior robot_file_inertia_prior(const ModelX& model, const EffectDesign& design,
                                               const BaseParameters& base);

/// A linear fit with the prior strength it was given.
struct PriorFit {
  LinearNominal fit;
  double strength = 0;                ///< 0: no prior was needed (or none given)
  double min_eigenvalue_without = 0;  ///< of M(q) of the fit without the prior [kg·m²] (with one)
  std::vector<PriorCandidate> candidates;  ///< ascending strength (choose_inertia_prior)
  std::string choice;                      ///< why `strength`, in a sentence (empty: no prior)
};

/// The ladder of strengths choose_inertia_prior tries: 0 and 1e-4 … 100 by decades.
std::vector<double> inertia_prior_ladder();

/// Least squares of `columns` on `selection`'s rows (fit_columns). With a `prior` (of `design`)
/// that has a floor, where M(q) of that fit has its smallest eigenvalue (min_mass_eigenvalue)
/// below the floor, the strength of the prior chosen on held-out error: every strength of
/// inertia_prior_ladder, and the smallest that lifts M(q) to the floor (bisection on log10 of
/// the strength in [−8, 2], to 1e-5 of a decade), is fitted on the training rows and scored on
/// the held-out ones; among those whose M(q) is above the floor, the lowest held-out error wins,
/// a weaker strength within 1 % of it preferred (the prior biases toward the robot file; it must
/// pay for itself). None above the floor: the lowest held-out error of all. Nothing held out:
/// the weakest above the floor (the strongest if none). A plain fit above the floor, or no prior
/// or no floor (≤ 0): the plain fit, no candidates.
PriorFit choose_inertia_prior(const ModelX& model, const EffectDesign& design,
                              const BaseParameters& base, const DesignGrams& grams,
                              const std::vector<int>& columns, FitSelection selection,
                              const RobotFileInertiaPrior* prior);

/// The fit on `selection`'s rows (every row, for the file) with the strength `judged` chose on
/// the training rows, raised to the smallest that lifts this fit's M(q) to the floor where it
/// does not (not where no strength lifted the judged fit either). Where `judged` needed none:
/// plain, or the smallest that lifts it if this fit's M(q) is below the floor. Without a prior
/// or a floor: the plain fit.
PriorFit refit_with_inertia_prior(const ModelX& model, const EffectDesign& design,
                                  const BaseParameters& base, const DesignGrams& grams,
                                  const std::vector<int>& columns, FitSelection selection,
                                  const RobotFileInertiaPrior* prior, const PriorFit& judged);

}  // namespace tpf::offline
