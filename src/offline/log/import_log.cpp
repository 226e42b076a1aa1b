#include "offline/log/import_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "offline/log/joint_side.hpp"
#include "offline/log/log_text.hpp"
#include "offline/log/read_log.hpp"
#include "offline/signal/segments.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// The columns of one recording (one file or several joined), rows aligned, with the first
/// file's line numbers for messages.
struct JoinedTable {
  std::string source;  ///< the first file
  long header_line = 0;
  long first_data_line = 0;
  std::size_t skipped_rows = 0;
  std::vector<std::string> notes;
  std::vector<long> lines;  ///< line of each row in the first file
  Eigen::VectorXd t;        ///< [s]
  std::map<std::string, Eigen::VectorXd> columns;
};

/// The time column in seconds (a sample index counts from the first row's index; no column:
/// row / rate_hz).
Eigen::VectorXd time_in_seconds(const CsvTable& table, const ImportMap& map) {
  if (map.time_unit == TimeUnit::Rate)
    return Eigen::VectorXd::LinSpaced(table.log.rows(), 0.0,
                                      static_cast<double>(table.log.rows() - 1)) /
           map.rate_hz;
  const Eigen::VectorXd raw = table.log.col(map.time_column);
  for (Eigen::Index r = 0; r < raw.size(); ++r)
    if (std::isnan(raw[r]))
      throw Error::at(table.log.source, table.first_data_line + static_cast<long>(r),
                      map.time_column, "the time is missing");
  switch (map.time_unit) {
    case TimeUnit::Seconds:
      return raw;
    case TimeUnit::Milliseconds:
      return raw / 1e3;
    case TimeUnit::Microseconds:
      return raw / 1e6;
    case TimeUnit::SampleIndex:
    case TimeUnit::Rate:
      break;
  }
  const double first = raw.size() > 0 ? raw[0] : 0.0;
  return (raw.array() - first) / map.rate_hz;
}

/// Source column names the map reads (time first, when there is a time column).
std::vector<std::string> wanted_columns(const ImportMap& map) {
  std::vector<std::string> wanted;
  if (!map.time_column.empty()) wanted.push_back(map.time_column);
  for (const ImportColumn& c : map.columns)
    for (int k = 1; k <= map.joints; ++k)
      wanted.push_back(map.source_name(c, k));
  return wanted;
}

/// For every row of `first_t`, the row of `other_t` with the same time (within `tolerance`),
/// or -1. Both increase where it matters; a two-pointer walk.
std::vector<Eigen::Index> match_in_time(const Eigen::VectorXd& first_t,
                                        const Eigen::VectorXd& other_t, double tolerance) {
  std::vector<Eigen::Index> match(static_cast<std::size_t>(first_t.size()), -1);
  Eigen::Index o = 0;
  for (Eigen::Index r = 0; r < first_t.size(); ++r) {
    while (o < other_t.size() && other_t[o] < first_t[r] - tolerance)
      ++o;
    if (o < other_t.size() && std::abs(other_t[o] - first_t[r]) <= tolerance)
      match[static_cast<std::size_t>(r)] = o;
  }
  return match;
}

/// Reads the files of one recording and puts their columns side by side (map.join).
JoinedTable join_files(const std::vector<std::filesystem::path>& files, const ImportMap& map,
                       ImportReport& report) {
  const std::vector<std::string> wanted = wanted_columns(map);
  std::vector<CsvTable> tables;
  for (const auto& file : files)
    tables.push_back(read_csv_table(file, &wanted));
  JoinedTable joined;
  const CsvTable& first = tables.front();
  joined.source = first.log.source;
  joined.header_line = first.header_line;
  joined.first_data_line = first.first_data_line;
  for (const CsvTable& table : tables) {
    joined.skipped_rows += table.log.quality.skipped_rows;
    joined.notes.insert(joined.notes.end(), table.log.quality.notes.begin(),
                        table.log.quality.notes.end());
  }
  for (const std::string& name : wanted)
    if (std::none_of(tables.begin(), tables.end(),
                     [&](const CsvTable& t) { return t.log.has(name); }))
      throw Error::at(
          first.log.source, first.header_line, name,
          "the column named by " + map.file + " is missing from the header" +
              (files.size() > 1 ? " of every one of the " + std::to_string(files.size()) + " files"
                                : std::string()));
  joined.t = time_in_seconds(first, map);
  const Eigen::Index rows = first.log.rows();
  // rows[f][r]: the row of file f that goes with row r of the first file (-1: none)
  std::vector<std::vector<Eigen::Index>> rows_of(tables.size());
  for (std::size_t f = 0; f < tables.size(); ++f) {
    if (f == 0 || map.join == JoinRule::Index) {
      if (tables[f].log.rows() != rows)
        throw Error(tables[f].log.source + ": " + std::to_string(tables[f].log.rows()) +
                    " data rows, but " + first.log.source + " has " + std::to_string(rows) +
                    ": files joined by sample index (" + map.file +
                    ", \"join\": \"index\") must have as many; nothing written");
      rows_of[f].resize(static_cast<std::size_t>(rows));
      for (Eigen::Index r = 0; r < rows; ++r)
        rows_of[f][static_cast<std::size_t>(r)] = r;
      continue;
    }
    rows_of[f] =
        match_in_time(joined.t, time_in_seconds(tables[f], map), 0.25 * median_step(joined.t));
  }
  std::vector<Eigen::Index> kept;
  for (Eigen::Index r = 0; r < rows; ++r) {
    const bool everywhere = std::all_of(rows_of.begin(), rows_of.end(), [&](const auto& m) {
      return m[static_cast<std::size_t>(r)] >= 0;
    });
    if (everywhere) kept.push_back(r);
  }
  report.unmatched_rows = static_cast<std::size_t>(rows) - kept.size();
  if (files.size() > 1)
    report.conversion_notes.push_back(std::to_string(files.size()) + " files joined by " +
                                      (map.join == JoinRule::Index ? "sample index" : "time") +
                                      ": " + std::to_string(kept.size()) + " samples" +
                                      (report.unmatched_rows > 0
                                           ? ", " + std::to_string(report.unmatched_rows) +
                                                 " rows of " + first.log.source +
                                                 " without a partner in time in every file, dropped"
                                           : std::string()));
  const auto n = static_cast<Eigen::Index>(kept.size());
  Eigen::VectorXd t(n);
  for (Eigen::Index k = 0; k < n; ++k)
    t[k] = joined.t[kept[static_cast<std::size_t>(k)]];
  joined.t = t;
  for (const Eigen::Index r : kept)
    joined.lines.push_back(first.first_data_line + static_cast<long>(r));
  for (const std::string& name : wanted) {
    std::size_t f = 0;
    while (!tables[f].log.has(name))
      ++f;
    const auto source = tables[f].log.col(name);
    Eigen::VectorXd column(n);
    for (Eigen::Index k = 0; k < n; ++k)
      column[k] = source[rows_of[f][static_cast<std::size_t>(kept[static_cast<std::size_t>(k)])]];
    joined.columns[name] = column;
  }
  return joined;
}

/// Rows to keep: each one's time is after the last kept row's.
std::vector<Eigen::Index> increasing_rows(const Eigen::VectorXd& t, const std::vector<long>& lines,
                                          ImportReport& report) {
  std::vector<Eigen::Index> keep;
  keep.reserve(static_cast<std::size_t>(t.size()));
  for (Eigen::Index r = 0; r < t.size(); ++r) {
    if (!keep.empty() && !(t[r] > t[keep.back()])) {
      if (report.not_increasing++ == 0)
        report.first_not_increasing_line = lines[static_cast<std::size_t>(r)];
      continue;
    }
    keep.push_back(r);
  }
  return keep;
}

void count_steps(const Eigen::VectorXd& t, const std::vector<Eigen::Index>& rows,
                 const std::vector<long>& lines, ImportReport& report) {
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double step = t[rows[k]] - t[rows[k - 1]];
    if (std::abs(step - report.nominal_step_s) > 0.1 * report.nominal_step_s)
      ++report.irregular_steps;
    if (step > 1.5 * report.nominal_step_s) ++report.gap_steps;
    if (step > report.largest_step_s) {
      report.largest_step_s = step;
      report.largest_step_line = lines[static_cast<std::size_t>(rows[k])];
    }
  }
}

/// Refuses a map's rate_hz that the recorded time (s, ms or µs) contradicts: a median step more
/// than 10 % off 1 / rate_hz. Rule 'regular' would rewrite every time stamp by the wrong clock,
/// rule 'keep' judge every step by it, and both write it into the log's header.
void check_rate_against_time(const Eigen::VectorXd& kept_t, const ImportMap& map,
                             const std::string& csv_source) {
  if (map.rate_hz <= 0.0 || map.time_unit == TimeUnit::SampleIndex ||
      map.time_unit == TimeUnit::Rate)
    return;
  const double nominal = 1.0 / map.rate_hz;
  const double median = median_step(kept_t);
  if (std::abs(median - nominal) <= 0.1 * nominal) return;
  throw Error::at(map.file, 0, "rate_hz",
                  log_text::printed("%.6g", map.rate_hz) + " Hz is a step of " +
                      log_text::printed("%.6g", nominal) + " s, but the time column of " +
                      csv_source + " steps " + log_text::printed("%.6g", median) +
                      " s at the median (" + log_text::printed("%.6g", 1.0 / median) +
                      " Hz): correct rate_hz or time.unit; nothing written");
}

}  // namespace

std::vector<std::string> ImportReport::lines() const {
  std::vector<std::string> out = reader_notes;
  out.push_back("time: " + std::to_string(rows_read) + " rows read, " +
                std::to_string(rows_written) + " written; nominal step " +
                log_text::printed("%.6g", nominal_step_s) + " s");
  if (not_increasing > 0)
    out.push_back("time: " + std::to_string(not_increasing) +
                  " rows dropped because their time does not increase (first on line " +
                  std::to_string(first_not_increasing_line) + ")");
  out.push_back("time: " + std::to_string(irregular_steps) +
                " irregular steps (off the nominal by > 10 %), " + std::to_string(gap_steps) +
                " of them gaps (> 1.5 nominal); largest step " +
                log_text::printed("%.6g", largest_step_s) + " s" +
                (irregular_steps > 0 ? " before line " + std::to_string(largest_step_line) : ""));
  if (made_regular)
    out.push_back("time: rule 'regular': t rewritten as k / rate_hz, at most " +
                  log_text::printed("%.3g", regular_max_shift_s) +
                  " s from the recorded time (no gap is left in the log)");
  else if (gap_steps > 0)
    out.push_back("time: rule 'keep': the " + std::to_string(gap_steps) +
                  " gaps stay in the log; every tool splits its segments there");
  out.insert(out.end(), conversion_notes.begin(), conversion_notes.end());
  return out;
}

Log import_log(const std::filesystem::path& csv, const ImportMap& map, ImportReport& report) {
  return import_log(std::vector<std::filesystem::path>{csv}, map, report);
}

Log import_log(const std::vector<std::filesystem::path>& files, const ImportMap& map,
               ImportReport& report) {
  if (files.size() != static_cast<std::size_t>(map.files))
    throw Error(map.file + ": files: the map reads " + std::to_string(map.files) +
                " file(s) per recording, given " + std::to_string(files.size()));
  report = ImportReport{};
  const JoinedTable table = join_files(files, map, report);
  report.reader_notes = table.notes;
  report.rows_read = static_cast<std::size_t>(table.t.size());
  const std::vector<Eigen::Index> rows = increasing_rows(table.t, table.lines, report);
  report.rows_written = rows.size();
  if (rows.size() < 2)
    throw Error::at(table.source, table.header_line, "",
                    std::to_string(report.rows_read) + " data rows" +
                        (table.skipped_rows > 0 ? " (and a cut last row, skipped)" : "") + ", " +
                        std::to_string(rows.size()) +
                        " with an increasing time: a log needs at least two; nothing written");
  Eigen::VectorXd kept_t(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k)
    kept_t[static_cast<Eigen::Index>(k)] = table.t[rows[k]];
  check_rate_against_time(kept_t, map, table.source);
  report.nominal_step_s = map.rate_hz > 0 ? 1.0 / map.rate_hz : median_step(kept_t);
  count_steps(table.t, rows, table.lines, report);
  if (map.timestamps == TimestampRule::Regular) {
    report.made_regular = true;
    for (Eigen::Index k = 0; k < kept_t.size(); ++k) {
      const double regular = kept_t[0] + static_cast<double>(k) / map.rate_hz;
      report.regular_max_shift_s =
          std::max(report.regular_max_shift_s, std::abs(kept_t[k] - regular));
      kept_t[k] = regular;
    }
  }

  Log log;
  log.source = files.front().string();
  for (const auto& [key, value] : map.metadata)
    log.meta.set(key, value);
  if (map.rate_hz > 0) log.meta.set("rate_hz", log_text::printed("%.17g", map.rate_hz));
  std::string names;
  for (const auto& file : files)
    names.append(names.empty() ? "" : " + ").append(file.filename().string());
  log.meta.set("imported_from", names);
  log.meta.set("import_map", std::filesystem::path(map.file).filename().string());
  log.columns.push_back("t");
  log.values.resize(kept_t.size(), 1);
  log.values.col(0) = kept_t;
  SourceColumns source;
  for (const auto& [name, column] : table.columns) {
    Eigen::VectorXd kept(kept_t.size());
    for (std::size_t k = 0; k < rows.size(); ++k)
      kept[static_cast<Eigen::Index>(k)] = column[rows[k]];
    source[name] = kept;
  }
  for (const auto& [prefix, values] :
       joint_side_columns(source, kept_t, map, report.conversion_notes))
    for (int k = 1; k <= map.joints; ++k)
      log.add_column(indexed_name(prefix, k), values.col(k - 1));
  log.quality.rows = rows.size();
  log.quality.missing_per_column.assign(log.columns.size(), 0);
  for (Eigen::Index c = 0; c < log.values.cols(); ++c)
    log.quality.missing_per_column[static_cast<std::size_t>(c)] =
        static_cast<std::size_t>(log.values.col(c).array().isNaN().count());
  return log;
}

}  // namespace tpf::offline
