// The parameter file's model as diagnose writes a fit into it, family by family.
#pragma once

#include <Eigen/Core>

#include "offline/effects/candidate_inputs.hpp"
#include "tpf/dynamics/base_parameters.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::offline {

template <int N>
struct WrittenModel {
  NominalModel<double, N>& nominal;
  StribeckParameters<double, N>& linear;  ///< the linear friction the Stribeck curves start from
  Eigen::VectorXd& payload;  ///< standard parameters (11N) of a payload, folded into the base
  const BaseParameters& base;
  const CandidateInputs& inputs;
  bool load_selected = false;  ///< some load-dependent friction coefficient is non-zero
};

}  // namespace tpf::offline
