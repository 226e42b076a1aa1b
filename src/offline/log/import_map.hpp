// The column map of `tpf import` (a small JSON file, docs/log-format.md "Importing"): which
// columns of a foreign CSV hold time, q, q̇, current or torque, torque sensor, temperature, in
// which units, for which joints.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace tpf::offline {

/// How the time column is read.
enum class TimeUnit { Seconds, Milliseconds, Microseconds, SampleIndex, Rate };
/// (Rate: no time column; t = row / rate_hz.)

/// What import does with the file's time stamps.
enum class TimestampRule {
  Keep,     ///< t as recorded (converted to s); steps > 1.5/rate stay gaps that tools split at
  Regular,  ///< t = k / rate_hz for the k-th kept row: for a fixed-rate recording whose time
            ///< stamps carry the recording computer's jitter
};

/// Which side of the gear a column is recorded on.
enum class Side { Joint, Motor };

/// How several files of one recording are put side by side.
enum class JoinRule {
  Index,  ///< row k of every file is one sample (the files must have as many rows)
  Time,   ///< rows whose time matches in every file (within a quarter of the median step)
};

/// One tpf column family (q, dq, i, …) and where it comes from. Per tpf joint k (or motor k,
/// side motor), in the log format's unit (SI; i in mA):
///   value = unit_factor[k] · (sign[k] · scale[k] · source value + offset[k])
/// with offset in the map's unit of the column.
struct ImportColumn {
  std::string prefix;  ///< tpf prefix: q, dq, ddq, i, tau, tau_sensor, tau_maker, temp
  std::string source;  ///< source column pattern, "{j}" replaced by the source joint number
                       ///< (a 1-joint map's may be a plain name, without "{j}")
  std::vector<std::string> sources;  ///< or one name per tpf joint (the map's "source" array)
  std::vector<std::string> unit;     ///< per joint, as written in the map
  std::vector<double> unit_factor;   ///< per joint, map unit → log format unit
  std::vector<double> scale;         ///< per joint: sign · scale
  std::vector<double> offset;        ///< per joint, in the map's unit
  Side side = Side::Joint;  ///< q, dq, ddq, i, tau: motor side goes through the transmission
  /// i only: the motor's torque constant [N·m/A] per motor, signed (τ_motor = K_t · i); empty:
  /// the current is written as recorded and the robot file's K_t converts it.
  std::vector<double> torque_constant;
  bool write_torque = false;  ///< i with torque_constant: write tau<j> [N·m], not i<j> [mA]
};

/// The cut-off of "derive" when the map gives none: on the measured Kinova Gen3 logs (1 kHz),
/// q̇ derived from q differs from the logged q̇ by 1.4–1.5 % RMS at 5–20 Hz, 1.9 % at 50 Hz,
/// 2.8 % at 100 Hz (opti_traj_testing1; docs/log-format.md). Also identify's q̈ cut-off.
inline constexpr double kDefaultDeriveCutoffHz = 15.0;

struct ImportMap {
  std::string file;  ///< the map's path, for messages
  int joints = 0;
  std::vector<int> joint_order;  ///< tpf joint k (1-based) takes source joint joint_order[k−1]
  std::string time_column;       ///< empty with TimeUnit::Rate
  TimeUnit time_unit = TimeUnit::Seconds;
  double rate_hz = 0.0;  ///< 0: not given (then the median step is the nominal one)
  TimestampRule timestamps = TimestampRule::Keep;
  std::vector<ImportColumn> columns;
  std::vector<std::pair<std::string, std::string>> metadata;  ///< written into the log
  /// Files per recording (inputs are taken in groups of this many and joined into one log).
  int files = 1;
  JoinRule join = JoinRule::Index;
  /// θ_motor = R·q, τ_joint = Rᵀ·τ_motor; R = diag(ratio)·coupling, in tpf joint order. Identity
  /// without a "transmission" key.
  Eigen::MatrixXd transmission;
  bool coupled = false;  ///< the coupling is not diagonal
  /// > 0: q̇ (when not mapped) and q̈ (when not mapped) are derived from q: a 2nd-order
  /// Butterworth run forward and backward (zero phase, −6 dB at the cut-off), then central
  /// differences; with a mapped q̇ the derived one is compared with it in the report.
  double derive_cutoff_hz = 0.0;

  bool has(const std::string& prefix) const;
  const ImportColumn& column(const std::string& prefix) const;

  /// Source column name of `column` for tpf joint k (1-based); a pattern without "{j}" (1-joint
  /// map) is the name itself.
  std::string source_name(const ImportColumn& column, int k) const;
};

/// Reads and checks a column map ("format": "tpf-import", "version": 1). Throws tpf::Error
/// "file: key: reason" on a missing or unknown key, an unknown unit, a joint order that is not
/// a permutation, a pattern without "{j}" in a map of several joints, no q/dq or no effort (i or
/// tau).
ImportMap load_import_map(const std::filesystem::path& path);

}  // namespace tpf::offline
