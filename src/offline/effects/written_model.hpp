// The parameter file's model as diagnose writes a fit into it, family by family.
#pragma once

#include <Eigen/Core>

#include "offline/common/run_time_types.hpp"
#include "offline/effects/candidate_inputs.hpp"
#include "tpf/dynamics/base_parameters.hpp"

namespace tpf::offline {

struct WrittenModel {
  NominalModelX& nominal;
  StribeckParametersX& linear;  ///< the linear friction the Stribeck curves start from
  Eigen::VectorXd& payload;     ///< standard parameters (11N) of a payload, folded into the base
  const BaseParameters& base;
  const CandidateInputs& inputs;
  bool load_selected = false;  ///< some load-dependent friction coefficient is non-zero

  int joints() const { return static_cast<int>(linear.coulomb.size()); }
};

}  // namespace tpf::offline
