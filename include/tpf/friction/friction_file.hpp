// Loading friction parameters from a JSON file (start-up code: allocates and throws tpf::Error
// naming the file and the field).
//
// File layout (one array per parameter, one number per joint, joints in chain order):
//   { "effort_unit": "N*m",                       // or "mA": the unit of every torque below
//     "coulomb": [...], "static": [...], "stribeck_velocity": [...], "stribeck_exponent": [...],
//     "viscous": [...], "load_coulomb": [...], "load_viscous": [...],     // load terms optional
//     "bristle_stiffness": [...], "bristle_damping": [...] }             // LuGre only
// Unknown keys are refused, so a typo never silently falls back to a default.
#pragma once

#include <string>

#include "tpf/friction/lugre.hpp"
#include "tpf/friction/stribeck.hpp"

namespace tpf {

/// Reads the Stribeck + viscous (+ load) parameters, as many joints as the file's arrays hold
/// (`joints` > 0: exactly that many); LuGre keys, if present, are validated and ignored. Throws
/// tpf::Error "path: field: reason" on a missing/unknown key, a wrong length or a bad value.
StribeckParameters<double, Eigen::Dynamic> load_stribeck_parameters(const std::string& path,
                                                                    int joints = 0);

/// Reads the LuGre parameters (the Stribeck keys plus bristle_stiffness and bristle_damping).
LuGreParameters<double, Eigen::Dynamic> load_lugre_parameters(const std::string& path,
                                                              int joints = 0);

/// load_stribeck_parameters for a program of N joints and scalar S (header-only conversion).
template <typename S, int N>
StribeckParameters<S, N> load_stribeck_parameters(const std::string& path) {
  return joint_count_cast<N, S>(load_stribeck_parameters(path, N == Eigen::Dynamic ? 0 : N));
}

/// load_lugre_parameters for a program of N joints and scalar S (header-only conversion).
template <typename S, int N>
LuGreParameters<S, N> load_lugre_parameters(const std::string& path) {
  return joint_count_cast<N, S>(load_lugre_parameters(path, N == Eigen::Dynamic ? 0 : N));
}

/// The "effort_unit" of the file ("N*m" or "mA").
std::string friction_effort_unit(const std::string& path);

}  // namespace tpf
