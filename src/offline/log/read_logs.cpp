#include "offline/log/read_logs.hpp"

#include <algorithm>
#include <cmath>

#include "offline/log/read_log.hpp"
#include "offline/signal/segments.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// Names of `first` that every log in `logs` has, in `first`'s order.
std::vector<std::string> common_columns(const std::vector<Log>& logs) {
  std::vector<std::string> common;
  for (const std::string& name : logs.front().columns)
    if (std::all_of(logs.begin(), logs.end(), [&](const Log& l) { return l.has(name); }))
      common.push_back(name);
  return common;
}

void note_dropped_columns(const std::vector<Log>& logs, const std::vector<std::string>& common,
                          std::vector<std::string>* notes) {
  if (notes == nullptr) return;
  for (const Log& log : logs) {
    std::string dropped;
    for (const std::string& name : log.columns)
      if (std::find(common.begin(), common.end(), name) == common.end())
        dropped.append(dropped.empty() ? "" : ", ").append(name);
    if (!dropped.empty())
      notes->push_back(log.source + ": columns not in every file, left out: " + dropped);
  }
}

/// Hands the reader's notes of `log` to `notes` (then said once, by the caller, and no longer in
/// the quality summary); kept in `log` when `notes` is null.
void hand_over_reader_notes(Log& log, std::vector<std::string>* notes) {
  if (notes == nullptr) return;
  notes->insert(notes->end(), log.quality.notes.begin(), log.quality.notes.end());
  log.quality.notes.clear();
}

}  // namespace

double file_seam_seconds(double median_step_s) {
  return std::max(1.0, 100.0 * (std::isfinite(median_step_s) ? median_step_s : 0.0));
}

Log read_logs(const std::vector<std::filesystem::path>& paths, std::vector<std::string>* notes,
              const ColumnFilter& keep_column) {
  if (paths.empty()) throw Error("no log file given");
  std::vector<Log> logs;
  logs.reserve(paths.size());
  for (const auto& path : paths) {
    logs.push_back(read_log(path, keep_column));
    hand_over_reader_notes(logs.back(), notes);
  }
  if (logs.size() == 1) return std::move(logs.front());

  const std::vector<std::string> columns = common_columns(logs);
  if (std::find(columns.begin(), columns.end(), "t") == columns.end())
    throw Error("the logs have no column in common");
  note_dropped_columns(logs, columns, notes);

  Log out;
  out.meta = logs.front().meta;
  out.columns = columns;
  Eigen::Index rows = 0;
  double step = 0.0;
  for (const Log& log : logs) {
    rows += log.rows();
    step = std::max(step, median_step(log.col("t")));
  }
  const double seam = file_seam_seconds(step);
  out.values.resize(rows, static_cast<Eigen::Index>(columns.size()));
  out.file_starts.clear();
  out.quality.missing_per_column.assign(columns.size(), 0);
  std::string files;
  Eigen::Index row = 0;
  double next_start = 0.0;
  for (const Log& log : logs) {
    out.file_starts.push_back(row);
    out.source.append(row == 0 ? "" : " + ").append(log.source);
    files.append(row == 0 ? "" : "; ").append(log.source);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const int from = log.column(columns[c]);
      out.values.col(static_cast<Eigen::Index>(c)).segment(row, log.rows()) = log.values.col(from);
      out.quality.missing_per_column[c] += log.quality.missing_per_column[from];
    }
    if (log.rows() > 0) {
      auto t = out.values.col(out.column("t")).segment(row, log.rows());
      const double shift = (row == 0 ? 0.0 : next_start - t[0]);
      t.array() += shift;
      next_start = t[t.size() - 1] + seam;
    }
    for (const std::size_t gap : log.quality.gap_rows)
      out.quality.gap_rows.push_back(static_cast<std::size_t>(row) + gap);
    if (row > 0) {
      out.quality.gap_rows.push_back(static_cast<std::size_t>(row));
      ++out.quality.seams;
    }
    out.quality.duration_s += log.quality.duration_s;
    out.quality.skipped_rows += log.quality.skipped_rows;
    out.quality.notes.insert(out.quality.notes.end(), log.quality.notes.begin(),
                             log.quality.notes.end());
    row += log.rows();
  }
  std::sort(out.quality.gap_rows.begin(), out.quality.gap_rows.end());
  out.quality.gaps = out.quality.gap_rows.size();
  out.quality.rows = static_cast<std::size_t>(rows);
  out.quality.files = logs.size();
  const auto rate = logs.front().meta.get("rate_hz");
  const bool same_rate = std::all_of(logs.begin(), logs.end(),
                                     [&](const Log& l) { return l.meta.get("rate_hz") == rate; });
  out.quality.rate_hz = same_rate ? logs.front().quality.rate_hz : 1.0 / step;
  if (!same_rate) {
    std::erase_if(out.meta.entries, [](const auto& e) { return e.first == "rate_hz"; });
    if (notes) notes->push_back("the files give different rate_hz: gaps use each file's own rate");
  }
  out.meta.set("files", files);
  return out;
}

Log read_logs(const std::vector<std::string>& paths, std::vector<std::string>* notes,
              const ColumnFilter& keep_column) {
  return read_logs(std::vector<std::filesystem::path>(paths.begin(), paths.end()), notes,
                   keep_column);
}

}  // namespace tpf::offline
