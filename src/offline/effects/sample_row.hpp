// What every column family sees at one sample: the motion, the rigid-body regressor, the
// direction of motion and the candidate inputs of that sample.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/common/run_time_types.hpp"
#include "offline/effects/candidate_inputs.hpp"
#include "offline/samples/joint_samples.hpp"

namespace tpf::offline {

struct SampleRow {
  EffectInputX motion;                   ///< q, q̇, q̈ and the gear ratios
  const Eigen::MatrixXd& regressor;      ///< Y(q, q̇, q̈)
  const Eigen::VectorXd& direction;      ///< sgn(q̇_j) when moving (|q̇_j| ≥ threshold), else 0
  const Eigen::VectorXd& held;           ///< the sign of the friction held at rest, 0 when moving
  const std::vector<int>& base_columns;  ///< regressor columns of the base parameters
  const CandidateInputs& inputs;
  const JointSamples& samples;
  Eigen::Index k;  ///< the sample's row in `samples` and in the inputs' per-sample tables

  int joints() const { return static_cast<int>(motion.q.size()); }
};

}  // namespace tpf::offline
