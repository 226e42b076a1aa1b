// What every column family sees at one sample: the motion, the rigid-body regressor, the
// direction of motion and the candidate inputs of that sample.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/effects/candidate_inputs.hpp"
#include "offline/identify/joint_samples.hpp"
#include "tpf/dynamics/regressor.hpp"
#include "tpf/effects/effect_input.hpp"

namespace tpf::offline {

template <int N>
struct SampleRow {
  EffectInput<double, N> motion;          ///< q, q̇, q̈ and the gear ratios
  const Regressor<double, N>& regressor;  ///< Y(q, q̇, q̈)
  const JointVector<double, N>& direction;  ///< sgn(q̇_j) when moving (|q̇_j| ≥ threshold), else 0
  const JointVector<double, N>& held;    ///< the sign of the friction held at rest, 0 when moving
  const std::vector<int>& base_columns;  ///< regressor columns of the base parameters
  const CandidateInputs& inputs;
  const JointSamples& samples;
  Eigen::Index k;  ///< the sample's row in `samples` and in the inputs' per-sample tables
};

}  // namespace tpf::offline
