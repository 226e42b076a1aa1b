// What the log reader found and did: missing values and gaps, for reports and terminal output.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace tpf::offline {

/// Data-quality record of one log. Missing values stay NaN in the data (never invented); gaps
/// are dropped cycles, dt > 1.5 / rate, and tools must never interpolate or differentiate across
/// them.
struct LogQuality {
  std::size_t rows = 0;
  std::vector<std::size_t> missing_per_column;  ///< empty field or 'nan', per column in file order
  std::size_t gaps = 0;                         ///< number of gaps
  std::vector<std::size_t> gap_rows;            ///< row index of the first sample after each gap
  double rate_hz = 0.0;          ///< rate used for gap detection (metadata, else median of dt)
  double duration_s = 0.0;       ///< t.back() − t.front() (several files: the sum of theirs)
  std::size_t files = 1;         ///< files the log was read from (read_logs)
  std::size_t seams = 0;         ///< of the gaps, those between two files (files − 1)
  std::size_t skipped_rows = 0;  ///< data rows of the file(s) left out of the log, each in `notes`
  /// What the reader left out or doubted, one line each, "file:line: field: what was found, and
  /// what was done" (a last row cut off, a rate_hz the time column contradicts).
  std::vector<std::string> notes;

  /// Total number of missing values over all columns.
  std::size_t missing_total() const;
  /// One or two lines for the terminal, e.g.
  /// "1440000 rows, 3600.0 s at 400 Hz; 12 gaps; 3 missing values (q2: 1, p3: 2)"; a log of
  /// several files begins "3 files, " and counts the seams: "4 gaps (2 between files)"; skipped
  /// rows are counted after the rows ("2 rows (1 more skipped), …") and each note follows on a
  /// line of its own.
  /// `columns` names the entries of missing_per_column (pass Log::columns); may be empty.
  std::string summary(const std::vector<std::string>& columns) const;
  /// Same without column names.
  std::string summary() const;
  /// Each note on a line of its own, indented ("\n  note"); empty without notes.
  std::string notes_text() const;
};

}  // namespace tpf::offline
