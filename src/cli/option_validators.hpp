// CLI11 validators shared by the subcommands: numbers that must be finite and inside an interval
// (CLI::Range lets NaN through: every comparison with NaN is false), whole numbers from a set,
// and file options that must not name a directory. A refused value stops the command before any
// work with "<option>: <what is wrong>; expected <what>".
#pragma once

#include <CLI/CLI.hpp>
#include <initializer_list>
#include <limits>

#include "offline/compensator_training/tcn_trainer.hpp"

namespace tpf::cli {

/// The longest simulated run, as a scenario's duration_s allows [s].
inline constexpr double kMaxSimulatedSeconds = 1e6;

/// An interval of the real line; an open end excludes its bound.
struct Interval {
  double low = -std::numeric_limits<double>::max();
  double high = std::numeric_limits<double>::max();
  bool low_open = false;
  bool high_open = false;
};

/// A finite number inside `interval` (NaN and ±inf refused). Text that is not a number is left
/// to CLI11's conversion, which names the option.
CLI::Validator number_in(const Interval& interval);

/// A finite number > 0 and ≤ `high`.
inline CLI::Validator positive(double high = std::numeric_limits<double>::max()) {
  return number_in({0.0, high, true, false});
}

/// A finite number ≥ `low`.
inline CLI::Validator at_least(double low) {
  return number_in({low});
}

/// A finite number ≥ 0.
inline CLI::Validator non_negative() {
  return at_least(0.0);
}

/// A finite number in [low, high).
inline CLI::Validator in_half_open(double low, double high) {
  return number_in({low, high, false, true});
}

/// The TCN target's low/high split cut-off [Hz]: in (0, Nyquist) of the training rate.
inline CLI::Validator split_cutoff_hz() {
  return number_in({0.0, 0.5 * offline::TcnTrainOptions{}.sample_rate_hz, true, true});
}

/// One of `values` (e.g. the hidden sizes the networks are compiled for).
CLI::Validator one_of(std::initializer_list<int> values);

/// An existing file that is not a directory: "<path> is a directory, not a file".
CLI::Validator input_file();

/// `input_file()`, or the word `keyword` (e.g. --pads none).
CLI::Validator input_file_or(const char* keyword);

/// Compensator weights: a file, or the path whose <stem>.joint<j>.json files exist (the loader
/// names those that are missing), never a directory.
CLI::Validator weights_path();

}  // namespace tpf::cli
