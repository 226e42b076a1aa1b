#include "offline/identify/inertia_prior.hpp"

#include <cmath>

#include "offline/effects/effect_columns.hpp"
#include "tpf/common/joint_counts.hpp"
#include "tpf/dynamics/regressor.hpp"

namespace tpf::offline {

template <int N>
ColumnPrior robot_file_prior(const Model<double, N>& model, const EffectDesign<N>& design,
                             const BaseParameters& base) {
  const JointVector<double, N> zero = JointVector<double, N>::Zero();
  const Eigen::VectorXd values =
      base.project(dynamic_parameters(model, zero, zero).head(11 * N).eval());
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

template <int N>
PriorFit<N> fit_with_inertia_prior(const Model<double, N>& model, const EffectDesign<N>& design,
                                   const BaseParameters& base, const DesignGrams& grams,
                                   const std::vector<int>& columns, FitSelection selection,
                                   const ColumnPrior* prior) {
  auto fit = [&](double strength) {
    if (prior) selection.prior = *prior;
    selection.prior.strength = strength;
    return linear_nominal(model, design, base, fit_columns(grams, columns, selection));
  };
  PriorFit<N> out{fit(0)};
  if (!prior) return out;
  out.min_eigenvalue_without = min_mass_eigenvalue(out.fit.nominal);
  const double floor =
      0.1 * min_mass_eigenvalue(linear_nominal(model, design, base, prior->mean).nominal);
  if (out.min_eigenvalue_without >= floor) return out;
  double weak = -8, strong = 2;  // log10 of the strength: below floor at `weak`
  out.fit = fit(std::pow(10.0, strong));
  if (min_mass_eigenvalue(out.fit.nominal) >= floor)
    for (int k = 0; k < 20; ++k) {
      const double middle = 0.5 * (weak + strong);
      LinearNominal<N> trial = fit(std::pow(10.0, middle));
      if (min_mass_eigenvalue(trial.nominal) >= floor) {
        strong = middle;
        out.fit = std::move(trial);
      } else {
        weak = middle;
      }
    }
  out.strength = std::pow(10.0, strong);
  return out;
}

#define TPF_INSTANTIATE_INERTIA_PRIOR(N)                                                          \
  template ColumnPrior robot_file_prior<N>(const Model<double, N>&, const EffectDesign<N>&,       \
                                           const BaseParameters&);                                \
  template PriorFit<N> fit_with_inertia_prior<N>(                                                 \
      const Model<double, N>&, const EffectDesign<N>&, const BaseParameters&, const DesignGrams&, \
      const std::vector<int>&, FitSelection, const ColumnPrior*);
TPF_FOR_EACH_JOINT_COUNT(TPF_INSTANTIATE_INERTIA_PRIOR)
#undef TPF_INSTANTIATE_INERTIA_PRIOR

}  // namespace tpf::offline
