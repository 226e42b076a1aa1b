#include "offline/log/import_log.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "offline/log/read_log.hpp"
#include "offline/signal/segments.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// The time column in seconds (a sample index counts from the first row's index).
Eigen::VectorXd time_in_seconds(const CsvTable& table, const ImportMap& map) {
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
      break;
  }
  const double first = raw.size() > 0 ? raw[0] : 0.0;
  return (raw.array() - first) / map.rate_hz;
}

/// Rows to keep: each one's time is after the last kept row's.
std::vector<Eigen::Index> increasing_rows(const Eigen::VectorXd& t, long first_line,
                                          ImportReport& report) {
  std::vector<Eigen::Index> keep;
  keep.reserve(static_cast<std::size_t>(t.size()));
  for (Eigen::Index r = 0; r < t.size(); ++r) {
    if (!keep.empty() && !(t[r] > t[keep.back()])) {
      if (report.not_increasing++ == 0) report.first_not_increasing_line = first_line + r;
      continue;
    }
    keep.push_back(r);
  }
  return keep;
}

void count_steps(const Eigen::VectorXd& t, const std::vector<Eigen::Index>& rows, long first_line,
                 ImportReport& report) {
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const double step = t[rows[k]] - t[rows[k - 1]];
    if (std::abs(step - report.nominal_step_s) > 0.1 * report.nominal_step_s)
      ++report.irregular_steps;
    if (step > 1.5 * report.nominal_step_s) ++report.gap_steps;
    if (step > report.largest_step_s) {
      report.largest_step_s = step;
      report.largest_step_line = first_line + rows[k];
    }
  }
}

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

/// Refuses a map's rate_hz that the recorded time (s, ms or µs) contradicts: a median step more
/// than 10 % off 1 / rate_hz. Rule 'regular' would rewrite every time stamp by the wrong clock,
/// rule 'keep' judge every step by it, and both write it into the log's header.
void check_rate_against_time(const Eigen::VectorXd& kept_t, const ImportMap& map,
                             const std::string& csv_source) {
  if (map.rate_hz <= 0.0 || map.time_unit == TimeUnit::SampleIndex) return;
  const double nominal = 1.0 / map.rate_hz;
  const double median = median_step(kept_t);
  if (std::abs(median - nominal) <= 0.1 * nominal) return;
  throw Error::at(map.file, 0, "rate_hz",
                  format("%.6g", map.rate_hz) + " Hz is a step of " + format("%.6g", nominal) +
                      " s, but the time column of " + csv_source + " steps " +
                      format("%.6g", median) + " s at the median (" + format("%.6g", 1.0 / median) +
                      " Hz): correct rate_hz or time.unit; nothing written");
}

}  // namespace

std::vector<std::string> ImportReport::lines() const {
  std::vector<std::string> out = reader_notes;
  out.push_back("time: " + std::to_string(rows_read) + " rows read, " +
                std::to_string(rows_written) + " written; nominal step " +
                format("%.6g", nominal_step_s) + " s");
  if (not_increasing > 0)
    out.push_back("time: " + std::to_string(not_increasing) +
                  " rows dropped because their time does not increase (first on line " +
                  std::to_string(first_not_increasing_line) + ")");
  out.push_back("time: " + std::to_string(irregular_steps) +
                " irregular steps (off the nominal by > 10 %), " + std::to_string(gap_steps) +
                " of them gaps (> 1.5 nominal); largest step " + format("%.6g", largest_step_s) +
                " s" +
                (irregular_steps > 0 ? " before line " + std::to_string(largest_step_line) : ""));
  if (made_regular)
    out.push_back("time: rule 'regular': t rewritten as k / rate_hz, at most " +
                  format("%.3g", regular_max_shift_s) +
                  " s from the recorded time (no gap is left in the log)");
  else if (gap_steps > 0)
    out.push_back("time: rule 'keep': the " + std::to_string(gap_steps) +
                  " gaps stay in the log; every tool splits its segments there");
  return out;
}

Log import_log(const std::filesystem::path& csv, const ImportMap& map, ImportReport& report) {
  std::vector<std::string> wanted{map.time_column};
  for (const ImportColumn& c : map.columns)
    for (int k = 1; k <= map.joints; ++k)
      wanted.push_back(map.source_name(c, k));
  const CsvTable table = read_csv_table(csv, &wanted);
  for (const std::string& name : wanted)
    if (!table.log.has(name))
      throw Error::at(table.log.source, table.header_line, name,
                      "the column named by " + map.file + " is missing from the header");

  report = ImportReport{};
  report.reader_notes = table.log.quality.notes;
  report.rows_read = static_cast<std::size_t>(table.log.rows());
  const Eigen::VectorXd t = time_in_seconds(table, map);
  const std::vector<Eigen::Index> rows = increasing_rows(t, table.first_data_line, report);
  report.rows_written = rows.size();
  if (rows.size() < 2)
    throw Error::at(
        table.log.source, table.header_line, "",
        std::to_string(report.rows_read) + " data rows" +
            (table.log.quality.skipped_rows > 0 ? " (and a cut last row, skipped)" : "") + ", " +
            std::to_string(rows.size()) +
            " with an increasing time: a log needs at least two; nothing written");
  Eigen::VectorXd kept_t(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t k = 0; k < rows.size(); ++k)
    kept_t[static_cast<Eigen::Index>(k)] = t[rows[k]];
  check_rate_against_time(kept_t, map, table.log.source);
  report.nominal_step_s = map.rate_hz > 0 ? 1.0 / map.rate_hz : median_step(kept_t);
  count_steps(t, rows, table.first_data_line, report);
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
  log.source = csv.string();
  for (const auto& [key, value] : map.metadata)
    log.meta.set(key, value);
  if (map.rate_hz > 0) log.meta.set("rate_hz", format("%.17g", map.rate_hz));
  log.meta.set("imported_from", csv.filename().string());
  log.meta.set("import_map", std::filesystem::path(map.file).filename().string());
  log.columns.push_back("t");
  for (const ImportColumn& c : map.columns)
    for (int k = 1; k <= map.joints; ++k)
      log.columns.push_back(indexed_name(c.prefix, k));
  log.values.resize(kept_t.size(), static_cast<Eigen::Index>(log.columns.size()));
  log.values.col(0) = kept_t;
  Eigen::Index out = 1;
  for (const ImportColumn& c : map.columns)
    for (int k = 1; k <= map.joints; ++k, ++out) {
      const auto source = table.log.col(map.source_name(c, k));
      for (std::size_t r = 0; r < rows.size(); ++r)
        log.values(static_cast<Eigen::Index>(r), out) = c.scale * source[rows[r]];
    }
  log.quality.rows = rows.size();
  log.quality.missing_per_column.assign(log.columns.size(), 0);
  for (Eigen::Index c = 0; c < log.values.cols(); ++c)
    log.quality.missing_per_column[static_cast<std::size_t>(c)] =
        static_cast<std::size_t>(log.values.col(c).array().isNaN().count());
  return log;
}

}  // namespace tpf::offline
