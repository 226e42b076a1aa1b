// Temperature-dependent viscous friction, τ_j += β_j·(T_j − T_ref)·q̇_j: an effect diagnosis
// finds and reports but the run time cannot evaluate (it has no temperature input).
#pragma once

#include <string_view>

#include "tpf/common/types.hpp"

namespace tpf {

struct ThermalFriction {
  static constexpr std::string_view key = "thermal";  ///< diagnose's name of the effect

  /// Parameter file, "added_effects": "thermal_viscous": [β_1 … β_N], "reference_temperature":
  /// T_ref [°C]; accepted only when absent or zero: a file that holds the effect is refused.
  template <typename Fields>
  static void refuse(Fields& added, int joints) {
    Eigen::VectorXd thermal = Eigen::VectorXd::Zero(joints);
    added.joint_vector("thermal_viscous", thermal, false);
    added.number("reference_temperature", 25.0, -273.15, 1e4);
    if (thermal.any())
      added.fail("thermal_viscous",
                 "temperature-dependent friction is not evaluated by the run-time nominal model "
                 "(it has no temperature input); set it to 0 or remove it to use the file "
                 "without it");
  }
};

}  // namespace tpf
