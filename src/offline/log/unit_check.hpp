// Checks of a log's units against its robot file, and of its dead channels: where the arm rests,
// the effort against the robot file's gravity torque (a factor of 1000, a gear ratio, a torque
// constant or a sign names the reading that would fit); positions against the joint limits;
// q̇ against Δq/Δt; efforts that are mostly exact zeros or a few distinct values.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace tpf::offline {

/// Samples × joints, in the tools' units (q [rad], q̇ [rad/s], effort as joint torque [N·m],
/// converted from mA with the robot file's K_t where the log holds currents).
struct UnitCheckInput {
  Eigen::VectorXd t;
  Eigen::MatrixXd q, dq, ddq, effort;
  Eigen::MatrixXd gravity;          ///< the robot file's gravity torque G(q) at each sample [N·m]
  Eigen::VectorXd gear_ratio;       ///< robot file, per joint
  Eigen::VectorXd torque_constant;  ///< robot file, output side [N·m/A]
  bool effort_is_current = false;   ///< the log's effort is i<j> (mA)
  Eigen::VectorXd lower, upper;     ///< position limits [rad]; ±∞ where none
  /// Per joint, true at a prismatic joint (q [m], q̇ [m/s], effort [N]); empty: all revolute.
  std::vector<bool> prismatic;
};

/// UnitCheckInput's members by reference: the checks of a long log without a copy of its columns.
struct UnitCheckView {
  const Eigen::VectorXd& t;
  const Eigen::MatrixXd &q, &dq, &ddq, &effort;
  const Eigen::MatrixXd& gravity;
  const Eigen::VectorXd &gear_ratio, &torque_constant;
  bool effort_is_current;
  const Eigen::VectorXd &lower, &upper;
  const std::vector<bool>& prismatic;
};

/// What the checks found, per finding one line "joint j: …".
struct LogChecks {
  std::vector<std::string> problems;  ///< units that do not fit, dead channels
  std::vector<std::string> notes;     ///< what could not be checked, and why
  std::vector<int> dead_joints;       ///< 1-based: effort mostly exact zeros or few values
  /// Per joint, the effort at rest over the gravity torque (least squares; NaN: not checked).
  std::vector<double> rest_factor;
};

/// Thresholds of the checks.
struct UnitCheckOptions {
  double rest_velocity = 0.05;  ///< every joint's |q̇| below this [rad/s]: the arm (nearly) rests
  double rest_acceleration = 0.5;  ///< and every joint's |q̈| below this [rad/s²]
  double moving_velocity = 0.05;   ///< a joint with |q̇| above this somewhere moves
  /// The same three at a prismatic joint [m/s, m/s², m/s]: a lift's top speed (0.07 m/s on a
  /// TIAGo torso) is of the order of the rotary thresholds, so a tenth of them.
  double rest_linear_velocity = 0.005;
  double rest_linear_acceleration = 0.05;
  double moving_linear_velocity = 0.005;
  std::size_t min_rest_samples = 20;
  /// Rest samples are compared where |G_j| is at least min_gravity [N·m] and min_gravity_share of
  /// its largest over the log (near its smallest, friction would decide the factor).
  double min_gravity = 0.2;
  double min_gravity_share = 0.25;
  double fitting_factor = 3.0;  ///< a rest factor within [1/x, x] fits (friction, K_t, model)
  /// The effort at rest more than this share RMS off its best multiple of G_j does not follow it.
  double rest_misfit = 0.6;
  double reading_tolerance = 1.25;  ///< a factor within ×/÷ this of a reading names it
  double dead_zero_fraction = 0.5;  ///< exact zeros in at least this share of samples: dead
  /// At most this many distinct values over a log in which the joint moves: dead.
  std::size_t dead_distinct_values = 64;
  double limit_margin = 0.05;  ///< [rad] beyond the limits before a sample counts as outside
};

/// Runs every check of `in`. Each problem says what was found, by how much, and the reading that
/// would fit ("joint 2 rests at 32× the gravity torque: is the effort joint torque read as motor
/// torque (× the gear ratio 32)?").
LogChecks check_log_units(const UnitCheckInput& in, const UnitCheckOptions& options = {});

/// The same checks of the columns `in` refers to.
LogChecks check_log_units(const UnitCheckView& in, const UnitCheckOptions& options = {});

}  // namespace tpf::offline
