// `tpf import`'s conversion of source columns to the log format's joint-side columns: units,
// scale, sign, offset, the transmission of motor-side columns, torque constants of currents, and
// q̇, q̈ derived from q.
#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "offline/log/import_map.hpp"

namespace tpf::offline {

/// Source columns by name, the rows the log keeps.
using SourceColumns = std::map<std::string, Eigen::VectorXd>;

/// The log's columns per tpf prefix in the log format's order (q, dq, ddq, the effort i or tau,
/// tau_sensor, tau_maker, temp), samples × joints, in the format's units (SI, i in mA):
/// - every family: unit_factor · (sign · scale · source + offset);
/// - side motor, with R = map.transmission: q = R⁻¹·θ (also q̇, q̈), τ_joint = Rᵀ·τ_motor;
/// - a current with torque constants: τ_motor = K_t·i; written as tau<j> = Rᵀ·τ_motor ("write":
///   "torque"), else as i<j> [mA] with the sign of its output-side constant r_jj·K_t folded in,
///   so that the robot file's positive K_t = |r_jj·K_t| converts it;
/// - map.derive_cutoff_hz > 0: q̇ and q̈ not mapped are derived from q (derive_rates); a mapped
///   q̇ is compared with the derived one.
/// `notes` receives one line per conversion done (and the comparison).
std::vector<std::pair<std::string, Eigen::MatrixXd>> joint_side_columns(
    const SourceColumns& source, const Eigen::VectorXd& t, const ImportMap& map,
    std::vector<std::string>& notes);

}  // namespace tpf::offline
