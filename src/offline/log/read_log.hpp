// Reading tpf logs (docs/log-format.md; implementation notes in docs/log-format-notes.md), and
// the plain numeric CSV tables `tpf import` brings in.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "offline/log/log.hpp"

namespace tpf::offline {

/// Whether a column, by name, is to be parsed and kept.
using ColumnFilter = std::function<bool(std::string_view name)>;

/// Reads a tpf log: '#' metadata, a header line, then comma-separated decimal numbers.
/// - a file that starts with the gzip magic (.csv.gz) is decompressed first;
/// - column order is free; unknown columns are kept; a 't' column is required;
/// - an empty field or 'nan' is a missing value: NaN in `values`, counted in `quality`;
/// - gaps (dt > 1.5 / rate) are counted in `quality`: rate from 'rate_hz' when the time column
///   agrees with it (median dt within 1 %, checked from 10 steps on), else the median dt's, with
///   a note in quality.notes naming the file, the metadata's rate and the measured one;
/// - a file that ends without a newline was cut inside its last row: that row is skipped
///   (quality.skipped_rows) and said in quality.notes with its line, never read as a number;
/// - errors name file, line and column: a 'tpf-log' major version > 1, a wrong field count, text
///   where a number belongs, an infinite value, a missing or non-increasing t, corrupt or
///   truncated gzip data.
/// The file is mapped (read in place, not copied) and parsed on two threads.
/// `keep_column` (all columns when empty): the columns to parse and keep, by name ('t' among
/// them); the others are skipped unparsed, as read_csv_table's.
Log read_log(const std::filesystem::path& path, const ColumnFilter& keep_column = {});

/// A numeric CSV file as read_csv_table found it, with the line numbers errors need.
struct CsvTable {
  Log log;  ///< source, '#' metadata, the kept columns in file order, values, missing counts
  std::vector<long> metadata_lines;  ///< line of each log.meta entry
  long header_line = 0;
  long first_data_line = 0;  ///< line of row 0; row r is on line first_data_line + r
};

/// The table layer of read_log, with no requirement on column names or time: '#' lines before
/// the header, the header, then numbers (gzip as read_log). Only the columns named in
/// `keep_columns` are parsed and kept (all when null); the others are skipped unparsed, so they
/// may hold text, but every line still needs the header's field count. Errors, and a cut last
/// row skipped and noted, as read_log's.
CsvTable read_csv_table(const std::filesystem::path& path,
                        const std::vector<std::string>* keep_columns = nullptr);
/// read_csv_table keeping the columns `keep_column` accepts (all when empty).
CsvTable read_csv_table(const std::filesystem::path& path, const ColumnFilter& keep_column);

}  // namespace tpf::offline
