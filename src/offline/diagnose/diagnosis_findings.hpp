// The last pass of diagnose: what it found and what is left, in plain sentences.
#pragma once

#include <string>
#include <vector>

#include "offline/diagnose/diagnose.hpp"

namespace tpf::offline {

/// The findings of `d`: the payload against the robot file's inertias, every claim (named or
/// ambiguous, its coefficients with standard errors, why one is not written), a regime the
/// written model does worse in than the declared one and why, and what is left unexplained
/// against the noise floor.
std::vector<std::string> diagnosis_findings(const EffectDiagnosis& d,
                                            const DiagnoseOptions& options);

}  // namespace tpf::offline
