#include "offline/log/log_quality.hpp"

#include <cstdio>
#include <numeric>

namespace tpf::offline {

std::size_t LogQuality::missing_total() const {
  return std::accumulate(missing_per_column.begin(), missing_per_column.end(), std::size_t{0});
}

std::string LogQuality::summary(const std::vector<std::string>& columns) const {
  char head[200];
  std::string text;
  if (files > 1) text = std::to_string(files) + " files, ";
  const std::string skipped =
      skipped_rows > 0 ? " (" + std::to_string(skipped_rows) + " more skipped)" : "";
  std::snprintf(head, sizeof head, "%zu rows%s, %.1f s at %g Hz; %zu gap%s", rows, skipped.c_str(),
                duration_s, rate_hz, gaps, gaps == 1 ? "" : "s");
  text += head;
  if (seams > 0) text += " (" + std::to_string(seams) + " between files)";
  text += "; ";
  const std::size_t missing = missing_total();
  if (missing == 0) return text + "no missing values" + notes_text();
  text += std::to_string(missing) + " missing value" + (missing == 1 ? "" : "s");
  std::string detail;
  int listed = 0;
  for (std::size_t c = 0; c < missing_per_column.size(); ++c) {
    if (missing_per_column[c] == 0) continue;
    if (listed++ == 8) {
      detail += ", ...";
      break;
    }
    if (!detail.empty()) detail += ", ";
    detail += (c < columns.size() ? columns[c] : "column " + std::to_string(c + 1)) + ": " +
              std::to_string(missing_per_column[c]);
  }
  return text + "\n  missing per column: " + detail + notes_text();
}

std::string LogQuality::notes_text() const {
  std::string text;
  for (const std::string& note : notes)
    text.append("\n  ").append(note);
  return text;
}

std::string LogQuality::summary() const {
  return summary({});
}

}  // namespace tpf::offline
