// The core's types at a run-time joint count (Eigen::Dynamic): what the offline tools hold, one
// compiled copy for an arm of any number of joints.
#pragma once

#include <Eigen/Core>

#include "tpf/effects/effect_input.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/friction/stribeck.hpp"
#include "tpf/model/data.hpp"
#include "tpf/model/model.hpp"

namespace tpf::offline {

using ModelX = Model<double, Eigen::Dynamic>;
using DataX = Data<double, Eigen::Dynamic>;
using StribeckParametersX = StribeckParameters<double, Eigen::Dynamic>;
using EffectInputX = EffectInput<double, Eigen::Dynamic>;
using tpf::NominalModelX;

}  // namespace tpf::offline
