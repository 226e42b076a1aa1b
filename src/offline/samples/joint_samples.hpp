// Folder samples/: the sample table of a log (JointSamples: joint state, effort, regimes, the
// held-out split), the rigid-body regressor of every sample (SampleRegressors) and the one
// function that decides which rows are held out (held_out_rows.hpp). Identification, diagnosis,
// the column families of effects/ and tpf validate read it; it depends on log/, signal/,
// regimes/ and fit/'s threading helpers only.
//
// The samples of a log that identification and diagnosis use: joint state, effort, regimes and
// the held-out split, with missing values flagged (never invented).
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/regimes/regime.hpp"
#include "offline/samples/repeated_motion.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::offline {

struct SampleOptions {
  RegimeOptions regimes;                 ///< static threshold etc. (label_regimes)
  double acceleration_cutoff_hz = 15.0;  ///< derive_acceleration when the log has no ddq<j>
  /// Held-out split of a one-file log: interleaved blocks of this length, every heldout_every-th
  /// held out (25 %). A several-file log (Log::file_starts) holds out its last file instead.
  double block_s = 5.0;
  int heldout_every = 4;
  /// false: nothing is held out (every sample fits; the caller scores on other logs, e.g. the
  /// measured loop's held-out files).
  bool hold_out = true;
  /// true: every row is held out (tpf validate: the log scores a model fitted on other logs).
  bool all_held_out = false;
  /// Several files: two files repeat one motion when the RMS of Δq over their common length is
  /// below this on every joint [rad] (repeated_motions); such files are held out together.
  double repeat_tolerance = 0.01;
};

/// Samples × joints matrices of one log (column j = joint j+1). Effort in N·m: a log of motor
/// currents is converted as it is read (`units`, which also converts back for reports).
struct JointSamples {
  std::string source;      ///< log path, for messages
  DriveUnits units;        ///< the log's effort unit (mA for i<j>, N·m for tau<j>) and K_t
  bool simulated = false;  ///< metadata 'source' says simulated
  Eigen::VectorXd t;
  Eigen::MatrixXd q, dq, ddq, effort;
  Eigen::MatrixXd temperature;               ///< temp<j> in °C; 0 columns when the log has none
  std::vector<std::vector<Regime>> regimes;  ///< [joint][sample], from label_regimes
  std::vector<char> valid;                   ///< every joint's q, dq, ddq, effort (and temp) finite
  /// The held-out split, as decide_held_out_rows (held_out_rows.hpp) set it: whether each sample
  /// is held out (a block, the held-out files, or every row), …
  std::vector<char> heldout;
  int heldout_file = 0;  ///< … the last file when the log is held out by file (1-based), else 0 …
  /// … and for a several-file log, its files in groups that repeat one motion (one group: every
  /// file repeats one motion, the log is split in blocks), the group held out (the last file's)
  /// and the repeated motions that joined files; empty for a one-file log.
  std::vector<std::vector<std::size_t>> heldout_file_groups;
  std::size_t heldout_group = 0;
  std::vector<RepeatedMotion> repeats;
  /// Sign of the last motion of each joint (|q̇| ≥ threshold): +1, −1, 0 before any motion or
  /// after a gap. Held through rests: a stopped geared joint keeps the friction it stopped with.
  Eigen::MatrixXd held_sign;
  std::size_t invalid_count = 0;       ///< samples skipped for a NaN (valid is false)
  std::size_t out_of_range_count = 0;  ///< of them, those with a value beyond ±kImplausibleValue

  int joints() const { return static_cast<int>(q.cols()); }
  Eigen::Index size() const { return t.size(); }
};

/// A value of a log no arm produces in SI units or mA (1e300 A, a corrupt field): such a sample
/// is skipped, as one with a missing value, and counted apart.
inline constexpr double kImplausibleValue = 1e9;

/// "32 skipped for a missing value (…)" and the out-of-range count when there are any: what the
/// tools print after a log's sample count.
std::string skipped_samples_text(const JointSamples& samples);

/// The columns identification and diagnosis read from a log, by name: t, q<j>, dq<j>, ddq<j>,
/// the effort i<j> or tau<j>, temp<j> (extract_joint_samples) and tau_sensor<j> (the torque-sensor
/// friction reference and report). A reader may skip the others (ground truth, pads) unparsed.
bool identification_column(std::string_view name);

/// Some row is held out (a file or blocks).
bool holds_rows_out(const JointSamples& samples);

/// Joint j's moving training samples (valid, not held out, Regime::Moving), at most `most` of
/// them evenly strided (0: all): the rows the residual searches of diagnose read.
std::vector<Eigen::Index> moving_training_rows(const JointSamples& samples, int j,
                                               std::size_t most = 0);

/// Empty when some valid sample of `samples` is held out (or `options.hold_out` is false: the
/// caller holds out other logs); else a sentence saying that nothing is held out, why (a one-file
/// log shorter than its first held-out block) and what to do.
std::string nothing_held_out_note(const JointSamples& samples, const SampleOptions& options);

/// Extracts the joint samples of `log`: q<j>, dq<j>, ddq<j> (or derive_acceleration of dq<j>),
/// the effort i<j> or tau<j> converted to N·m with `torque_constant` (the robot file's K_t per
/// joint, drive_units), temp<j> when every joint has one, and the held-out split
/// (decide_held_out_rows). Throws tpf::Error naming the log when
/// required columns are missing, K_t has another joint count, or there are fewer than 100 valid
/// samples.
JointSamples extract_joint_samples(const Log& log, const Eigen::VectorXd& torque_constant,
                                   const SampleOptions& options = {});

}  // namespace tpf::offline
