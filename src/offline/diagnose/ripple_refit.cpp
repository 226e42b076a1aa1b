#include "offline/diagnose/ripple_refit.hpp"

#include "offline/diagnose/residual_analysis.hpp"
#include "offline/effects/output_ripple_columns.hpp"

namespace tpf::offline {
namespace {

/// The output-ripple group of joint j, or nullptr.
const FeatureGroup* ripple_group(const std::vector<FeatureGroup>& groups, int j) {
  for (const FeatureGroup& g : groups)
    if (g.key == OutputRippleColumns::key && g.joint == j) return &g;
  return nullptr;
}

}  // namespace

RippleFrequencies refitted_ripple_frequencies(const EffectDesign& design, const DesignGrams& grams,
                                              const JointSamples& s,
                                              const std::vector<int>& declared_columns,
                                              const FitSelection& selection) {
  const CandidateInputs& inputs = design.candidates();
  RippleFrequencies out{inputs.ripple_cycles, inputs.ripple_periods};
  std::vector<int> joints;
  std::vector<Eigen::VectorXd> declared_parts;
  for (int j = 0; j < s.joints(); ++j) {
    const FeatureGroup* g = ripple_group(design.groups(), j);
    if (!g || !(inputs.ripple_periods.size() > j) || inputs.ripple_periods[j] < 1.0 ||
        inputs.ripple_periods[j] > kFewRipplePeriods)
      continue;
    std::vector<int> columns = declared_columns;
    columns.insert(columns.end(), g->columns.begin(), g->columns.end());
    Eigen::VectorXd theta = fit_columns(grams, columns, selection);
    for (int c : g->columns)
      theta[c] = 0.0;  // the declared part of the fit beside the ripple
    joints.push_back(j);
    declared_parts.push_back(std::move(theta));
  }
  if (joints.empty()) return out;
  const std::vector<Eigen::MatrixXd> predictions = design.predict_each(s, declared_parts);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const int j = joints[i];
    const Eigen::VectorXd residual = s.effort.col(j) - predictions[i].col(j);
    const OutputRipple ripple = joint_output_ripple(s, residual, j);
    if (ripple.cycles > 0) {
      out.cycles[j] = ripple.cycles;
      out.periods[j] = ripple.periods;
    }
  }
  return out;
}

}  // namespace tpf::offline
