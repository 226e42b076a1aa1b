// `tpf import`: a foreign CSV (plain or .gz) → a tpf log, driven by an ImportMap.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "offline/log/import_map.hpp"
#include "offline/log/log.hpp"

namespace tpf::offline {

/// What the import found in the file's time stamps and did about them (docs/log-format.md,
/// "Importing"). Nothing is dropped or changed without being counted here.
struct ImportReport {
  std::size_t rows_read = 0;
  std::size_t rows_written = 0;
  std::size_t not_increasing = 0;  ///< rows dropped: time equal to or before the kept row before
  long first_not_increasing_line = 0;
  double nominal_step_s = 0.0;      ///< 1 / rate_hz of the map, else the median step
  std::size_t irregular_steps = 0;  ///< kept steps off the nominal one by more than 10 %
  std::size_t gap_steps = 0;        ///< of those, steps > 1.5 × nominal (gaps tools split at)
  double largest_step_s = 0.0;
  long largest_step_line = 0;        ///< line of the row after the largest step
  bool made_regular = false;         ///< rule "regular": t rewritten as k / rate_hz
  double regular_max_shift_s = 0.0;  ///< largest |t_recorded − t_regular| (rule "regular")
  /// The CSV reader's, "file:line: what was found, and what was done": a row the file ends
  /// inside, skipped (not among rows_read).
  std::vector<std::string> reader_notes;
  /// Several files: rows of the other files no row of the first matched in time (join "time"),
  /// dropped.
  std::size_t unmatched_rows = 0;
  /// What was converted and how (join, transmission, torque constants, derived rates and their
  /// agreement with a logged velocity), one line each.
  std::vector<std::string> conversion_notes;

  /// Lines for the terminal, e.g. "time: 1942 rows, step 0.001 s: 0 irregular steps", the
  /// reader's notes first.
  std::vector<std::string> lines() const;
};

/// Reads `csv` (only the columns the map names; others may hold text) and builds the tpf log:
/// t [s], then per tpf joint k the map's families in the log format's units (q1..qN, dq1..dqN,
/// i<k> in mA or tau<k> in N·m, tau_sensor<k>, tau_maker<k>, temp<k>), metadata from the map,
/// rate_hz, and where it came from. Time rule: rows whose time does not increase are dropped and
/// counted; steps are kept as recorded (rule "keep": a step > 1.5 nominal stays a gap) or
/// rewritten on the regular grid (rule "regular"); `report` says how many of each.
/// Throws tpf::Error naming the file, line and column: a column of the map missing from the
/// header, a missing time, text in a mapped column, a wrong field count, corrupt gzip.
Log import_log(const std::filesystem::path& csv, const ImportMap& map, ImportReport& report);

/// The same for one recording kept in map.files files, joined row by row (join "index": the
/// files must have as many rows) or by time stamp (join "time": the rows of the first file whose
/// time every other file has, within a quarter of its median step; the others dropped and
/// counted). A mapped column is read from the first file that has it. Then, per the map: scale,
/// sign, offset and units; motor-side columns through the transmission (q = R⁻¹·θ,
/// τ = Rᵀ·τ_motor, τ_motor = K_t·i); q̇ and q̈ derived from q (map.derive_cutoff_hz).
Log import_log(const std::vector<std::filesystem::path>& files, const ImportMap& map,
               ImportReport& report);

}  // namespace tpf::offline
