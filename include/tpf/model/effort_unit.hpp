// Motor current and joint torque: the one place where a log's or a drive's effort (mA or N·m)
// meets the N·m the core computes in. tpf computes every torque in SI; current is converted with
// the robot file's torque constants where it enters (log reading, hardware adapters) and back
// where a person wants it (reports of a log in mA).
//
//   τ [N·m] = K_t [N·m/A] · i [mA] / 1000,   K_t = Model::torque_constant (output side)
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>

#include "tpf/common/error.hpp"
#include "tpf/common/types.hpp"
#include "tpf/model/model.hpp"

namespace tpf {

/// The unit of an effort column: motor current in mA (log columns i<j>) or joint torque in N·m
/// (tau<j>).
enum class EffortUnit : unsigned char { NewtonMetre, Milliampere };

/// "N*m" or "mA": the unit's name in files and reports.
inline const char* effort_unit_name(EffortUnit unit) noexcept {
  return unit == EffortUnit::Milliampere ? "mA" : "N*m";
}

/// The unit named "mA" or "N*m"; throws tpf::Error for anything else.
inline EffortUnit parse_effort_unit(std::string_view name) {
  if (name == "mA") return EffortUnit::Milliampere;
  if (name == "N*m") return EffortUnit::NewtonMetre;
  throw Error("effort unit must be \"mA\" or \"N*m\", got \"" + std::string(name) + "\"");
}

/// The unit of a log's effort column prefix: "i" → mA, "tau" → N·m (Log::effort_prefix).
inline EffortUnit effort_unit_of_column(std::string_view prefix) {
  if (prefix == "i") return EffortUnit::Milliampere;
  if (prefix == "tau") return EffortUnit::NewtonMetre;
  throw Error("an effort column is i<j> (mA) or tau<j> (N*m), got \"" + std::string(prefix) +
              "<j>\"");
}

/// τ = K_t·i/1000 [N·m] of motor currents i [mA] (K_t of `model`). Allocation-free: the form a
/// hardware adapter calls per cycle.
template <typename S, int N>
JointVector<S, N> torque_from_current(const Model<S, N>& model,
                                      const NoDeduce<JointVector<S, N>>& current_ma) noexcept {
  return model.torque_constant.cwiseProduct(current_ma) / S(1000);
}

/// i = 1000·τ/K_t [mA] of joint torques τ [N·m]: the inverse of torque_from_current.
template <typename S, int N>
JointVector<S, N> current_from_torque(const Model<S, N>& model,
                                      const NoDeduce<JointVector<S, N>>& torque) noexcept {
  return (S(1000) * torque).cwiseQuotient(model.torque_constant);
}

/// The effort unit of a log with the drives of one robot file, for the offline tools that convert
/// whole columns (rows = samples, column j = joint j + 1): torque = effort·diag(K_t/1000) for a
/// log in mA, unchanged for one in N·m; `to_effort` is the inverse (what a report of an mA log
/// prints). Build it with drive_units(model, unit).
struct DriveUnits {
  EffortUnit unit = EffortUnit::NewtonMetre;
  Eigen::VectorXd torque_constant;  ///< K_t per joint [N·m/A], from the robot file

  const char* name() const noexcept { return effort_unit_name(unit); }
  int joints() const noexcept { return static_cast<int>(torque_constant.size()); }
  /// N·m per effort unit of joint j: K_t/1000 for mA, 1 for N·m.
  double newton_metres_per_unit(int j) const {
    return unit == EffortUnit::Milliampere ? torque_constant[j] / 1000.0 : 1.0;
  }
  /// Joint j's effort `e` (the log's unit) in N·m.
  double to_torque(int j, double e) const { return e * newton_metres_per_unit(j); }
  /// Joint j's torque `tau` [N·m] in the log's unit.
  double to_effort(int j, double tau) const { return tau / newton_metres_per_unit(j); }
  /// Samples × joints efforts in N·m (column j converted with joint j's K_t).
  Eigen::MatrixXd to_torque(const Eigen::MatrixXd& effort) const {
    check_columns(effort.cols());
    Eigen::MatrixXd tau = effort;
    for (int j = 0; j < joints(); ++j)
      tau.col(j) *= newton_metres_per_unit(j);
    return tau;
  }
  /// Samples × joints torques [N·m] in the log's unit.
  Eigen::MatrixXd to_effort(const Eigen::MatrixXd& torque) const {
    check_columns(torque.cols());
    Eigen::MatrixXd e = torque;
    for (int j = 0; j < joints(); ++j)
      e.col(j) /= newton_metres_per_unit(j);
    return e;
  }

 private:
  void check_columns(Eigen::Index columns) const {
    if (columns != torque_constant.size())
      throw Error("DriveUnits: " + std::to_string(columns) + " effort columns for " +
                  std::to_string(torque_constant.size()) + " joints");
  }
};

/// The drive units of `model`'s drives (its torque constants) for effort in `unit`.
template <typename S, int N>
DriveUnits drive_units(const Model<S, N>& model, EffortUnit unit) {
  return {unit, model.torque_constant.template cast<double>()};
}

}  // namespace tpf
