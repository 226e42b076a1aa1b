// The robot file's inertias as a prior on the identified rigid body, as strong as M(q) needs.
#pragma once

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

/// A linear fit with the prior strength it was given.
template <int N>
struct PriorFit {
  LinearNominal<N> fit;
  double strength = 0;                ///< 0: no prior was needed (or none given)
  double min_eigenvalue_without = 0;  ///< of M(q) of the fit without the prior [kg·m²] (with one)
  /// A tenth of the smallest eigenvalue of M(q) of the prior's mean, the robot file's own [kg·m²]
  /// (with a prior). Not positive where the robot file's own M(q) is not positive definite (a
  /// joint with no inertia of its own or beyond it): no floor to lift the fit's to, no prior.
  double floor = 0;
};

/// Least squares of `columns` on `selection`'s rows (fit_columns). With a `prior`, where M(q) of
/// that fit has its smallest eigenvalue (min_mass_eigenvalue, 200 poses) below a tenth of the
/// prior's own, the fit with the smallest strength of `prior` that lifts it there: bisection on
/// log10 of the strength in [−8, 2] (20 halvings: to 1e-5 of a decade); the strength 100 if even
/// that does not. Without a floor (PriorFit::floor ≤ 0) the fit without the prior.
template <int N>
PriorFit<N> fit_with_inertia_prior(const Model<double, N>& model, const EffectDesign<N>& design,
                                   const BaseParameters& base, const DesignGrams& grams,
                                   const std::vector<int>& columns, FitSelection selection,
                                   const ColumnPrior* prior);

}  // namespace tpf::offline
