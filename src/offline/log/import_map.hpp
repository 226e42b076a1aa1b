// The column map of `tpf import` (a small JSON file, docs/log-format.md "Importing"): which
// columns of a foreign CSV hold time, q, q̇, current or torque, torque sensor, temperature, in
// which units, for which joints.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace tpf::offline {

/// How the time column is read.
enum class TimeUnit { Seconds, Milliseconds, Microseconds, SampleIndex };

/// What import does with the file's time stamps.
enum class TimestampRule {
  Keep,     ///< t as recorded (converted to s); steps > 1.5/rate stay gaps that tools split at
  Regular,  ///< t = k / rate_hz for the k-th kept row: for a fixed-rate recording whose time
            ///< stamps carry the recording computer's jitter
};

/// One tpf column family (q, dq, i, …) and where it comes from.
struct ImportColumn {
  std::string prefix;  ///< tpf prefix: q, dq, ddq, i, tau, tau_sensor, tau_maker, temp
  std::string source;  ///< source column pattern, "{j}" replaced by the source joint number
                       ///< (a 1-joint map's may be a plain name, without "{j}")
  std::string unit;    ///< as written in the map
  double scale = 1.0;  ///< tpf value = scale · source value
};

struct ImportMap {
  std::string file;  ///< the map's path, for messages
  int joints = 0;
  std::vector<int> joint_order;  ///< tpf joint k (1-based) takes source joint joint_order[k−1]
  std::string time_column;
  TimeUnit time_unit = TimeUnit::Seconds;
  double rate_hz = 0.0;  ///< 0: not given (then the median step is the nominal one)
  TimestampRule timestamps = TimestampRule::Keep;
  std::vector<ImportColumn> columns;
  std::vector<std::pair<std::string, std::string>> metadata;  ///< written into the log

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
