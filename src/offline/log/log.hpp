// A tpf log in memory: metadata, named columns and a samples × columns matrix (docs/log-format.md).
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "offline/log/log_metadata.hpp"
#include "offline/log/log_quality.hpp"

namespace tpf::offline {

/// One log. Units as in docs/log-format.md: t [s], q [rad], dq [rad/s], ddq [rad/s²], i [mA],
/// tau [N·m], p [kPa]. Missing values are NaN. Unknown columns are carried along unchanged.
struct Log {
  std::string source;  ///< file path, for messages
  LogMetadata meta;
  std::vector<std::string> columns;  ///< in file order
  Eigen::MatrixXd values;            ///< rows = samples, cols = columns; missing = NaN
  LogQuality quality;
  /// A log read from several files (concatenated in time, each file its own segment): the row
  /// where each file begins, ascending, first 0 ({0} for one file). Held-out-by-file scoring
  /// splits here.
  std::vector<Eigen::Index> file_starts{0};

  /// Index of column `name`, or -1 when absent.
  int column(std::string_view name) const;
  bool has(std::string_view name) const { return column(name) >= 0; }
  /// Column `name` as a vector view. Throws tpf::Error "<source>: column '<name>' is missing".
  Eigen::Ref<const Eigen::VectorXd> col(std::string_view name) const;
  Eigen::Ref<Eigen::VectorXd> col(std::string_view name);
  /// Number of samples.
  Eigen::Index rows() const { return values.rows(); }
  /// Number of files the log was read from (file_starts.size()).
  std::size_t file_count() const { return file_starts.size(); }
  /// Rows [first, second) of file f.
  std::pair<Eigen::Index, Eigen::Index> file_rows(std::size_t f) const;
  /// Path of file f: from the 'files' metadata that read_logs writes, else `source`.
  std::string file_path(std::size_t f) const;

  /// N, the largest j with q<j> present (0 when there is none). Throws tpf::Error naming the
  /// first missing column when any of q1..qN, dq1..dqN is absent.
  int joint_count() const;
  /// Number of pad pressure columns p<k>.
  int pad_count() const;
  /// "i" when i1..iN are all present (effort in mA), else "tau" when tau1..tauN are (N·m).
  /// Throws tpf::Error when neither set is complete.
  std::string effort_prefix() const;

  /// Appends a column (NaN-filled when `data` is empty). Throws when the name exists or the
  /// length differs from rows().
  void add_column(std::string name, const Eigen::VectorXd& data = {});
};

/// "<prefix><j>", e.g. indexed_name("dq", 3) == "dq3".
std::string indexed_name(std::string_view prefix, int j);

}  // namespace tpf::offline
