// A payload judged against the robot file's inertias (CAD), after the effects diagnose selected:
// the rigid body held at the robot file's base parameters, friction and the selected effects
// refitted with and without a body on the last link.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "offline/diagnose/diagnose.hpp"
#include "offline/diagnose/effect_selection.hpp"
#include "offline/fit/gram_fit.hpp"

namespace tpf::offline {

/// The payload check on `grams` over `groups`, the rigid body's columns held at `cad` (a
/// P-vector, zero elsewhere); `selected` are the groups the selection added (indices into
/// `groups`). Standard errors inflated by the largest of `variance_inflation`. A payload must also
/// remove min_improvement of each fold's held-out SSE in `transfer` (none for a one-file log).
CadPayloadCheck judge_cad_payload(const DesignGrams& grams, const std::vector<FeatureGroup>& groups,
                                  const Eigen::VectorXd& cad, const std::vector<int>& selected,
                                  const std::vector<TransferFold>& transfer,
                                  const FitSelection& selection,
                                  const Eigen::VectorXd& variance_inflation,
                                  const DiagnoseOptions& options);

}  // namespace tpf::offline
