#include "offline/identify/inertia_prior.hpp"

#include <Eigen/Cholesky>
#include <cmath>

#include "offline/effects/effect_columns.hpp"
#include "tpf/common/joint_counts.hpp"
#include "tpf/dynamics/regressor.hpp"

namespace tpf::offline {

template <int N>
MassMatrixProbe<N>::MassMatrixProbe(const NominalModel<double, N>& like) {
  Data<double, N> data;
  Regressor<double, N> Y0, Yi;
  const JointVector<double, N> zero = JointVector<double, N>::Zero();
  for (const JointVector<double, N>& q : mass_check_poses(like.model)) {
    compute_regressor(like.model, data, q, zero, zero, Y0);
    Eigen::MatrixXd& map = maps_.emplace_back(N * N, like.base_count);
    for (int i = 0; i < N; ++i) {
      compute_regressor(like.model, data, q, zero, JointVector<double, N>::Unit(i), Yi);
      for (int c = 0; c < like.base_count; ++c)
        map.col(c).segment(N * i, N) = Yi.col(like.base_columns[c]) - Y0.col(like.base_columns[c]);
    }
  }
}

template <int N>
bool MassMatrixProbe<N>::above(const NominalModel<double, N>& nominal, double floor) const {
  for (const Eigen::MatrixXd& map : maps_) {
    const Eigen::Matrix<double, N * N, 1> m = map * nominal.base_values.head(nominal.base_count);
    const Eigen::Map<const JointMatrix<double, N>> M(m.data());
    const JointMatrix<double, N> shifted =
        0.5 * (M + M.transpose()) - floor * JointMatrix<double, N>::Identity();
    if (Eigen::LLT<JointMatrix<double, N>>(shifted).info() != Eigen::Success) return false;
  }
  return true;
}

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
RobotFileInertiaPrior<N> robot_file_inertia_prior(const Model<double, N>& model,
                                                  const EffectDesign<N>& design,
                                                  const BaseParameters& base) {
  RobotFileInertiaPrior<N> out;
  out.prior = robot_file_prior(model, design, base);
  const NominalModel<double, N> own = linear_nominal(model, design, base, out.prior.mean).nominal;
  out.floor = 0.1 * min_mass_eigenvalue(own);
  if (out.floor > 0) out.probe = MassMatrixProbe<N>(own);
  return out;
}

template <int N>
PriorFit<N> fit_with_inertia_prior(const Model<double, N>& model, const EffectDesign<N>& design,
                                   const BaseParameters& base, const DesignGrams& grams,
                                   const std::vector<int>& columns, FitSelection selection,
                                   const RobotFileInertiaPrior<N>* prior) {
  auto fit = [&](double strength) {
    if (prior) selection.prior = prior->prior;
    selection.prior.strength = strength;
    return linear_nominal(model, design, base, fit_columns(grams, columns, selection));
  };
  PriorFit<N> out{fit(0)};
  if (!prior) return out;
  out.min_eigenvalue_without = min_mass_eigenvalue(out.fit.nominal);
  const double floor = prior->floor;
  if (!(floor > 0) || out.min_eigenvalue_without >= floor) return out;
  const MassMatrixProbe<N>& probe = prior->probe;
  double weak = -8, strong = 2;  // log10 of the strength: below floor at `weak`
  out.fit = fit(std::pow(10.0, strong));
  if (probe.above(out.fit.nominal, floor))
    for (int k = 0; k < 20; ++k) {
      const double middle = 0.5 * (weak + strong);
      LinearNominal<N> trial = fit(std::pow(10.0, middle));
      if (probe.above(trial.nominal, floor)) {
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
  template class MassMatrixProbe<N>;                                                              \
  template RobotFileInertiaPrior<N> robot_file_inertia_prior<N>(                                  \
      const Model<double, N>&, const EffectDesign<N>&, const BaseParameters&);                    \
  template PriorFit<N> fit_with_inertia_prior<N>(                                                 \
      const Model<double, N>&, const EffectDesign<N>&, const BaseParameters&, const DesignGrams&, \
      const std::vector<int>&, FitSelection, const RobotFileInertiaPrior<N>*);
TPF_FOR_EACH_JOINT_COUNT(TPF_INSTANTIATE_INERTIA_PRIOR)
#undef TPF_INSTANTIATE_INERTIA_PRIOR

}  // namespace tpf::offline
