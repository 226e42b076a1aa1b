#include "offline/log/joint_side.hpp"

#include <Eigen/LU>
#include <cmath>
#include <cstdio>

#include "offline/log/derived_rates.hpp"
#include "offline/log/log_text.hpp"

namespace tpf::offline {
namespace {

using Columns = std::vector<std::pair<std::string, Eigen::MatrixXd>>;

std::string list(const Eigen::VectorXd& v, const char* pattern) {
  std::string out;
  for (Eigen::Index k = 0; k < v.size(); ++k)
    out.append(k ? ", " : "").append(log_text::printed(pattern, v[k]));
  return out;
}

/// A family in the log format's unit, per joint (or motor): unit · (scale · source + offset).
Eigen::MatrixXd scaled(const SourceColumns& source, const ImportMap& map, const ImportColumn& c) {
  Eigen::MatrixXd out(source.begin()->second.size(), map.joints);
  for (int k = 0; k < map.joints; ++k) {
    const auto j = static_cast<std::size_t>(k);
    out.col(k) = c.unit_factor[j] *
                 (c.scale[j] * source.at(map.source_name(c, k + 1)).array() + c.offset[j]);
  }
  return out;
}

/// θ = R·q per sample (rows) → q = R⁻¹·θ.
Eigen::MatrixXd motor_to_joint_position(const Eigen::MatrixXd& motor, const Eigen::MatrixXd& r) {
  return r.partialPivLu().solve(motor.transpose()).transpose();
}

/// A current's family: i<j> as recorded, or through the torque constants and the transmission.
std::pair<std::string, Eigen::MatrixXd> current_column(const Eigen::MatrixXd& current_ma,
                                                       const ImportMap& map, const ImportColumn& c,
                                                       std::vector<std::string>& notes) {
  if (c.torque_constant.empty()) return {"i", current_ma};
  const Eigen::VectorXd kt = Eigen::VectorXd::Map(c.torque_constant.data(), map.joints);
  const Eigen::MatrixXd motor_torque = current_ma * kt.asDiagonal() / 1000.0;
  const bool motor = c.side == Side::Motor;
  if (c.write_torque) {
    notes.push_back(
        std::string("effort: tau<j> [N*m] = ") +
        (motor ? "R^T * K_t * i (motor currents through the transmission)" : "K_t * i") +
        ", K_t = " + list(kt, "%.6g") + " N*m/A");
    return {"tau", motor ? Eigen::MatrixXd(motor_torque * map.transmission) : motor_torque};
  }
  const Eigen::VectorXd output_kt =
      motor ? Eigen::VectorXd(kt.cwiseProduct(map.transmission.diagonal())) : kt;
  const Eigen::VectorXd sign = output_kt.array().sign();
  notes.push_back("effort: i<j> [mA], the sign of the output-side torque constant folded in (" +
                  list(sign, "%+.0f") + "); the robot file's torque_constant should be " +
                  list(output_kt.cwiseAbs(), "%.6g") + " N*m/A");
  return {"i", current_ma * sign.asDiagonal()};
}

/// Per joint, RMS(derived − logged) / RMS(logged) over the samples where both are defined.
Eigen::VectorXd relative_difference(const Eigen::MatrixXd& derived, const Eigen::MatrixXd& logged) {
  Eigen::VectorXd out(derived.cols());
  for (Eigen::Index k = 0; k < derived.cols(); ++k) {
    double diff = 0.0, ref = 0.0;
    for (Eigen::Index r = 0; r < derived.rows(); ++r)
      if (std::isfinite(derived(r, k)) && std::isfinite(logged(r, k))) {
        diff += std::pow(derived(r, k) - logged(r, k), 2);
        ref += logged(r, k) * logged(r, k);
      }
    out[k] = ref > 0.0 ? 100.0 * std::sqrt(diff / ref) : std::nan("");
  }
  return out;
}

/// q̇ and q̈ from q where the map does not give them; a mapped q̇ compared with the derived one.
void derive_missing_rates(const Eigen::VectorXd& t, const ImportMap& map, Columns& out,
                          std::vector<std::string>& notes) {
  const Eigen::MatrixXd& q = out.front().second;
  Eigen::MatrixXd velocity(q.rows(), q.cols()), acceleration(q.rows(), q.cols());
  for (Eigen::Index k = 0; k < q.cols(); ++k) {
    const DerivedRates rates = derive_rates(t, q.col(k), map.derive_cutoff_hz);
    velocity.col(k) = rates.velocity;
    acceleration.col(k) = rates.acceleration;
  }
  const std::string filter = "derived from q (Butterworth 2nd order forward and backward, " +
                             log_text::printed("%.6g", map.derive_cutoff_hz) +
                             " Hz, central differences; NaN at each segment's ends)";
  auto at = out.begin() + 1;
  if (map.has("dq")) {
    notes.push_back("dq: as logged; " + filter + " it differs by " +
                    list(relative_difference(velocity, at->second), "%.2g") +
                    " % RMS of the logged dq, per joint");
    ++at;
  } else {
    at = out.insert(at, {"dq", velocity}) + 1;
    notes.push_back("dq: " + filter);
  }
  if (!map.has("ddq")) {
    out.insert(at, {"ddq", acceleration});
    notes.push_back("ddq: " + filter);
  }
}

}  // namespace

Columns joint_side_columns(const SourceColumns& source, const Eigen::VectorXd& t,
                           const ImportMap& map, std::vector<std::string>& notes) {
  Columns out;
  bool motor_side = false;
  for (const ImportColumn& c : map.columns) {
    Eigen::MatrixXd values = scaled(source, map, c);
    const bool motor = c.side == Side::Motor;
    motor_side = motor_side || motor;
    if (c.prefix == "i") {
      out.push_back(current_column(values, map, c, notes));
      continue;
    }
    if (motor && c.prefix == "tau")
      values = values * map.transmission;  // τ_joint = Rᵀ·τ_motor, per sample row
    else if (motor)
      values = motor_to_joint_position(values, map.transmission);
    out.emplace_back(c.prefix, values);
  }
  if (motor_side)
    notes.push_back(std::string("transmission: motor-side columns mapped to the joints, R = ") +
                    (map.coupled ? "diag(ratio)*coupling" : "diag(ratio)") + ", diag(R) " +
                    list(map.transmission.diagonal(), "%.6g"));
  if (map.derive_cutoff_hz > 0.0) derive_missing_rates(t, map, out, notes);
  return out;
}

}  // namespace tpf::offline
