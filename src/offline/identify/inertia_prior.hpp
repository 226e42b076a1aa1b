// The robot file's inertias as a prior on the identified rigid body, as strong as M(q) needs.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/identify/effect_design.hpp"
#include "offline/identify/gram_fit.hpp"
#include "offline/identify/identify.hpp"
#include "tpf/dynamics/base_parameters.hpp"
#include "tpf/model/model.hpp"

namespace tpf::offline {

/// The robot file's own rigid body as a prior on `design`'s rigid-body columns: their base values
/// β·π of the file's inertias and armature (strength 0: set it to use it).
template <int N>
ColumnPrior robot_file_prior(const Model<double, N>& model, const EffectDesign<N>& design,
                             const BaseParameters& base);

/// M(q) at check_consistency's poses as a linear map of the base values: per pose, column i of
/// M is (Y(q, 0, e_i) − Y(q, 0, 0)).cols(base_columns)·base_values, the regressors computed
/// once, so that each of the bisection's trials costs products instead of (N + 1)·200
/// regressor passes.
template <int N>
class MassMatrixProbe {
 public:
  MassMatrixProbe() = default;  ///< no poses: above() holds
  /// For models with the kinematics and base columns of `like`.
  explicit MassMatrixProbe(const NominalModel<double, N>& like);
  /// Whether every eigenvalue of M(q) (symmetrised) of `nominal` exceeds `floor` at every pose: a
  /// Cholesky factor of M − floor·1 exists (the first pose without one ends the test).
  bool above(const NominalModel<double, N>& nominal, double floor) const;

 private:
  std::vector<Eigen::MatrixXd> maps_;  ///< per pose: (N·N) × base_count, column-major M
};

/// The robot file's inertias as a prior on one design's fits, built once for all of them.
template <int N>
struct RobotFileInertiaPrior {
  ColumnPrior prior;  ///< robot_file_prior (strength 0)
  /// A tenth of the smallest eigenvalue of the robot file's own M(q) [kg·m²]: what the fits'
  /// is lifted to. Not positive where the robot file's own M(q) is not positive definite (a joint
  /// with no inertia of its own or beyond it): no floor to lift the fits' to, no prior.
  double floor = 0;
  MassMatrixProbe<N> probe;  ///< for the design's base columns (where there is a floor)
};

template <int N>
RobotFileInertiaPrior<N> robot_file_inertia_prior(const Model<double, N>& model,
                                                  const EffectDesign<N>& design,
                                                  const BaseParameters& base);

/// A linear fit with the prior strength it was given.
template <int N>
struct PriorFit {
  LinearNominal<N> fit;
  double strength = 0;                ///< 0: no prior was needed (or none given)
  double min_eigenvalue_without = 0;  ///< of M(q) of the fit without the prior [kg·m²] (with one)
};

/// Least squares of `columns` on `selection`'s rows (fit_columns). With a `prior` (of `design`),
/// where M(q) of that fit has its smallest eigenvalue (min_mass_eigenvalue, 200 poses) below the
/// prior's floor, the fit with the smallest strength of the prior that lifts it there: bisection
/// on log10 of the strength in [−8, 2] (20 halvings: to 1e-5 of a decade); the strength 100 if
/// even that does not. Without a floor (≤ 0) the fit without the prior.
template <int N>
PriorFit<N> fit_with_inertia_prior(const Model<double, N>& model, const EffectDesign<N>& design,
                                   const BaseParameters& base, const DesignGrams& grams,
                                   const std::vector<int>& columns, FitSelection selection,
                                   const RobotFileInertiaPrior<N>* prior);

}  // namespace tpf::offline
