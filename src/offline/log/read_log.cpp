#include "offline/log/read_log.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <initializer_list>
#include <limits>
#include <memory>
#include <set>
#include <thread>
#include <utility>

#include "offline/common/not_a_number.hpp"
#include "offline/log/file_text.hpp"
#include "offline/signal/segments.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// Below this many bytes of data the second thread costs more than it saves.
constexpr std::size_t kParallelBytes = 256 << 10;

/// Joins text pieces (also sidesteps a GCC 12 -Wrestrict false positive on "literal" + string).
std::string concat(std::initializer_list<std::string_view> parts) {
  std::string text;
  for (const std::string_view part : parts)
    text.append(part);
  return text;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

/// Splits off the line at `pos` (without '\n' and a trailing '\r') and advances `pos`.
std::string_view next_line(std::string_view text, std::size_t& pos) {
  const std::size_t end = std::min(text.find('\n', pos), text.size());
  std::string_view line = text.substr(pos, end - pos);
  pos = end + 1;
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

/// The first problem found in a chunk of data lines.
struct ParseError {
  std::size_t row = std::numeric_limits<std::size_t>::max();
  int column = -1;  // -1: the line as a whole
  std::string message;
};

/// Result of parsing one chunk of data lines into rows [first_row, ...) of the matrix.
struct ChunkResult {
  std::vector<std::size_t> missing;
  ParseError error;
  std::exception_ptr exception;
};

std::size_t count_fields(const char* begin, const char* end) {
  return 1 + static_cast<std::size_t>(std::count(begin, end, ','));
}

/// A line with the wrong number of fields.
std::string field_count_message(std::size_t expected, std::size_t found) {
  return concat({"expected ", std::to_string(expected), " fields, found ", std::to_string(found)});
}

/// Parses lines in [begin, end) (each ending in '\n', except possibly the last) into rows
/// first_row.. of `values`: field c goes to column target[c] of `values`, or is skipped unparsed
/// when target[c] < 0 (its count still checked). Stops at the first malformed line. Never throws.
void parse_chunk(const char* begin, const char* end, std::size_t first_row,
                 const std::vector<int>& target, Eigen::MatrixXd& values, ChunkResult& result) {
  try {
    const std::size_t columns = target.size();
    // From this column on every field is skipped: only the rest of the line's commas are counted.
    std::size_t skipped_tail = columns;
    while (skipped_tail > 0 && target[skipped_tail - 1] < 0)
      --skipped_tail;
    const std::size_t rows = static_cast<std::size_t>(values.rows());
    double* const data = values.data();
    result.missing.assign(static_cast<std::size_t>(values.cols()), 0);
    std::size_t row = first_row;
    const char* p = begin;
    while (p < end) {
      const char* line_end = static_cast<const char*>(std::memchr(p, '\n', end - p));
      if (line_end == nullptr) line_end = end;
      const char* content_end = (line_end > p && line_end[-1] == '\r') ? line_end - 1 : line_end;
      const auto fail = [&](int column, std::string message) {
        result.error = {row, column, std::move(message)};
      };
      const char* field = p;
      for (std::size_t c = 0; c < columns; ++c) {
        while (field < content_end && (*field == ' ' || *field == '\t'))
          ++field;
        if (c == skipped_tail) {  // c fields read, each ended by a comma
          const std::size_t found =
              c + 1 + static_cast<std::size_t>(std::count(field, content_end, ','));
          if (found != columns) {
            fail(-1, field_count_message(columns, found));
            return;
          }
          break;
        }
        double value = kNaN;
        const char* after = field;
        if (target[c] < 0) {
          after = static_cast<const char*>(std::memchr(field, ',', content_end - field));
          if (after == nullptr) after = content_end;
        } else if (field < content_end && *field != ',') {
          const char* number = (*field == '+') ? field + 1 : field;
          const auto [ptr, ec] = std::from_chars(number, content_end, value);
          after = ptr;
          while (after < content_end && (*after == ' ' || *after == '\t'))
            ++after;
          if (ec != std::errc{} || (after < content_end && *after != ',')) {
            const char* stop = std::find(field, content_end, ',');
            fail(static_cast<int>(c),
                 concat({"'", std::string_view(field, stop - field),
                         ec == std::errc::result_out_of_range ? "' is out of range for a double"
                                                              : "' is not a number"}));
            return;
          }
          if (std::isinf(value)) {
            fail(static_cast<int>(c),
                 concat({"'", std::string_view(field, after - field), "' is not a finite number"}));
            return;
          }
        }
        if (target[c] >= 0) {
          if (std::isnan(value)) {
            value = kNaN;
            ++result.missing[static_cast<std::size_t>(target[c])];
          }
          data[static_cast<std::size_t>(target[c]) * rows + row] = value;
        }
        const bool last = c + 1 == columns;
        if ((!last && after >= content_end) || (last && after < content_end)) {
          fail(-1, field_count_message(columns, count_fields(p, content_end)));
          return;
        }
        field = after + 1;
      }
      ++row;
      p = line_end + 1;
    }
  } catch (...) {
    result.exception = std::current_exception();
  }
}

/// Where the data lines [begin, end) are split for two threads: just after the first line end
/// past the middle, or `end` (no split) when the data is small or has no line end there.
const char* split_point(const char* begin, const char* end) {
  if (static_cast<std::size_t>(end - begin) < kParallelBytes) return end;
  const char* middle = begin + (end - begin) / 2;
  const void* line_end = std::memchr(middle, '\n', static_cast<std::size_t>(end - middle));
  return line_end != nullptr ? static_cast<const char*>(line_end) + 1 : end;
}

/// The '\n' in [begin, split) and in [split, end), the second counted on a helper thread.
std::pair<std::size_t, std::size_t> count_line_ends(const char* begin, const char* split,
                                                    const char* end) {
  std::size_t second = 0;
  std::thread helper;
  if (split < end)
    helper = std::thread([&] { second = static_cast<std::size_t>(std::count(split, end, '\n')); });
  const auto first = static_cast<std::size_t>(std::count(begin, split, '\n'));
  if (helper.joinable()) helper.join();
  return {first, second};
}

/// The end of [begin, end) without its trailing blank lines and spaces.
const char* without_trailing_blanks(const char* begin, const char* end) {
  while (end > begin && (end[-1] == '\n' || end[-1] == '\r' || end[-1] == ' ' || end[-1] == '\t'))
    --end;
  return end;
}

/// A file that ends without a newline was cut, most likely inside its last row (a recorder that
/// stopped mid-write): that row's last field may be a cut number. The row is left out of the data
/// [data_begin, data_end) and said in the table's quality; a last line with more fields than the
/// header (`fields`) is no cut and stays, for the parser's error. Returns the data's new end.
const char* drop_unterminated_row(const std::string& file, const char* data_begin,
                                  const char* data_end, const char* text_end, std::size_t fields,
                                  CsvTable& table) {
  if (data_end == data_begin || std::find(data_end, text_end, '\n') != text_end) return data_end;
  const char* row = data_end;
  while (row > data_begin && row[-1] != '\n')
    --row;
  if (count_fields(row, data_end) > fields) return data_end;
  const long line = table.first_data_line + std::count(data_begin, row, '\n');
  ++table.log.quality.skipped_rows;
  table.log.quality.notes.emplace_back(
      Error::at(file, line, "",
                "the file ends without a newline, inside this row: a cut file? The row is "
                "skipped, its last field may be cut short")
          .what());
  return without_trailing_blanks(data_begin, row);
}

/// The table in `text`, the contents of `file`.
CsvTable parse_csv_table(const std::string& file, std::string_view text,
                         const ColumnFilter& keep_column) {
  CsvTable table;
  Log& log = table.log;
  log.source = file;

  // Metadata lines, then the header.
  std::size_t pos =
      text.starts_with("\xEF\xBB\xBF") ? 3 : 0;  // UTF-8 byte-order mark (spreadsheets)
  long line_no = 0;
  std::string_view header;
  bool have_header = false;
  while (pos < text.size()) {
    const std::string_view line = next_line(text, pos);
    ++line_no;
    if (trim(line).empty()) continue;
    if (line.front() != '#') {
      header = line;
      have_header = true;
      break;
    }
    const std::string_view body = trim(line.substr(1));
    const std::size_t colon = body.find(':');
    table.metadata_lines.push_back(line_no);
    if (colon == std::string_view::npos) {
      log.meta.entries.emplace_back(std::string(), std::string(body));
      continue;
    }
    log.meta.entries.emplace_back(std::string(trim(body.substr(0, colon))),
                                  std::string(trim(body.substr(colon + 1))));
  }
  if (!have_header)
    throw Error::at(
        file, 0, "",
        text.empty() ? "the file is empty (no header line)" : "no header line after the metadata");

  // Header: names, unique, non-empty (a name in double quotes loses them).
  table.header_line = line_no;
  std::vector<std::string> names;
  {
    std::set<std::string_view> seen;
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = std::min(header.find(',', start), header.size());
      std::string_view name = trim(header.substr(start, comma - start));
      if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
        name = trim(name.substr(1, name.size() - 2));
      const std::string where = "column " + std::to_string(names.size() + 1);
      if (name.empty()) throw Error::at(file, table.header_line, where, "empty column name");
      if (!seen.insert(name).second)
        throw Error::at(file, table.header_line, std::string(name), "column name appears twice");
      names.emplace_back(name);
      if (comma == header.size()) break;
      start = comma + 1;
    }
  }
  std::vector<int> target(names.size(), -1);
  for (std::size_t c = 0; c < names.size(); ++c) {
    if (keep_column && !keep_column(names[c])) continue;
    target[c] = static_cast<int>(log.columns.size());
    log.columns.push_back(names[c]);
  }

  // Data region: drop trailing blank lines, and a last row the file ends inside.
  const char* const data_begin = text.data() + std::min(pos, text.size());
  const char* const text_end = text.data() + text.size();
  table.first_data_line = table.header_line + 1;
  const char* const data_end =
      drop_unterminated_row(file, data_begin, without_trailing_blanks(data_begin, text_end),
                            text_end, names.size(), table);
  const std::size_t columns = log.columns.size();

  // Split at a line boundary near the middle; count the lines of both halves, then parse both
  // halves, at once.
  const char* const split = split_point(data_begin, data_end);
  const std::pair<std::size_t, std::size_t> line_ends =
      count_line_ends(data_begin, split, data_end);
  const std::size_t second_first_row = line_ends.first;
  const std::size_t rows = data_end > data_begin ? line_ends.first + line_ends.second + 1 : 0;
  log.values.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(columns));
  ChunkResult first, second;
  if (split < data_end) {
    std::thread helper(
        [&] { parse_chunk(split, data_end, second_first_row, target, log.values, second); });
    parse_chunk(data_begin, split, 0, target, log.values, first);
    helper.join();
  } else {
    parse_chunk(data_begin, data_end, 0, target, log.values, first);
    second.missing.assign(columns, 0);
  }
  for (const ChunkResult* chunk : {&first, &second})
    if (chunk->exception) std::rethrow_exception(chunk->exception);
  const ParseError& error = first.error.row <= second.error.row ? first.error : second.error;
  if (!error.message.empty())
    throw Error::at(file, table.first_data_line + static_cast<long>(error.row),
                    error.column >= 0 ? names[static_cast<std::size_t>(error.column)] : "",
                    error.message);
  log.quality.rows = rows;
  log.quality.missing_per_column.resize(columns);
  for (std::size_t c = 0; c < columns; ++c)
    log.quality.missing_per_column[c] = first.missing[c] + second.missing[c];
  return table;
}

/// The metadata rate_hz is checked against the time column from this many steps on (fewer say
/// little about the rate) ...
constexpr Eigen::Index kRateCheckSteps = 10;
/// ... and the two agree when the median step is within this fraction of 1 / rate_hz.
constexpr double kRateTolerance = 0.01;

/// The rate gaps are found at: the metadata's rate_hz (`rate`, at `line` of `file`) when the time
/// column `t` agrees with it, else the time column's own (1 / its median step), with a note in
/// `quality` naming both. NaN `rate` (no metadata): the time column's; 0 for fewer than 2 rows.
double rate_for_gaps(const std::string& file, long line, double rate, const Eigen::VectorXd& t,
                     LogQuality& quality) {
  if (t.size() < 2) return std::isnan(rate) ? 0.0 : rate;
  const double step = median_step(t);
  if (std::isnan(rate)) return 1.0 / step;
  if (t.size() <= kRateCheckSteps || std::abs(step * rate - 1.0) <= kRateTolerance) return rate;
  char message[320];
  std::snprintf(message, sizeof message,
                "the metadata says %.6g Hz, but the time column's median step is %.6g s (%.6g "
                "Hz); the time column is used: gaps are found at %.6g Hz",
                rate, step, 1.0 / step, 1.0 / step);
  quality.notes.emplace_back(Error::at(file, line, "rate_hz", message).what());
  return 1.0 / step;
}

}  // namespace

CsvTable read_csv_table(const std::filesystem::path& path, const ColumnFilter& keep_column) {
  const FileText file_text(path);
  try {
    CsvTable table = parse_csv_table(path.string(), file_text.text(), keep_column);
    file_text.check_complete();
    return table;
  } catch (const Error&) {
    file_text.check_complete();  // what failed to parse was the zeros past a truncated file's end
    throw;
  }
}

CsvTable read_csv_table(const std::filesystem::path& path,
                        const std::vector<std::string>* keep_columns) {
  if (keep_columns == nullptr) return read_csv_table(path, ColumnFilter{});
  return read_csv_table(path, [keep_columns](std::string_view name) {
    return std::find(keep_columns->begin(), keep_columns->end(), name) != keep_columns->end();
  });
}

Log read_log(const std::filesystem::path& path, const ColumnFilter& keep_column) {
  CsvTable table = read_csv_table(path, keep_column);
  Log& log = table.log;
  const std::string& file = log.source;
  const auto line_of = [&](std::string_view key) {
    for (std::size_t e = 0; e < log.meta.entries.size(); ++e)
      if (log.meta.entries[e].first == key) return table.metadata_lines[e];
    return 0L;
  };
  const long version_line = line_of("tpf-log");
  try {
    const int version = log.meta.version();
    if (version > 1)
      throw Error::at(file, version_line, "tpf-log",
                      concat({"version ", std::to_string(version),
                              " is newer than this reader understands (1); update tpf"}));
  } catch (const Error& e) {
    if (version_line > 0 && std::string_view(e.what()).substr(0, file.size()) == file) throw;
    throw Error::at(file, version_line, "tpf-log", "not a version number");
  }
  try {
    static_cast<void>(log.meta.rate_hz());
  } catch (const Error&) {
    throw Error::at(file, line_of("rate_hz"), "rate_hz",
                    concat({"'", *log.meta.get("rate_hz"), "' is not a positive number"}));
  }
  if (!log.has("t"))
    throw Error::at(file, table.header_line, "t", "the required time column is missing");

  // Time: present on every line and increasing.
  const Eigen::VectorXd t = log.col("t");
  for (Eigen::Index r = 0; r < t.size(); ++r) {
    const long line = table.first_data_line + static_cast<long>(r);
    if (std::isnan(t[r])) throw Error::at(file, line, "t", "the sample time is missing");
    if (r > 0 && !(t[r] > t[r - 1])) {
      char message[160];
      std::snprintf(message, sizeof message,
                    "t = %.17g does not increase (previous line has t = %.17g)", t[r], t[r - 1]);
      throw Error::at(file, line, "t", message);
    }
  }

  // Quality: gaps (dt > 1.5 / rate).
  LogQuality& quality = log.quality;
  quality.rate_hz = rate_for_gaps(file, line_of("rate_hz"), log.meta.rate_hz(), t, quality);
  if (t.size() > 1) {
    quality.duration_s = t[t.size() - 1] - t[0];
    const double gap_step = 1.5 / quality.rate_hz;
    for (Eigen::Index r = 1; r < t.size(); ++r)
      if (t[r] - t[r - 1] > gap_step) quality.gap_rows.push_back(static_cast<std::size_t>(r));
  }
  quality.gaps = quality.gap_rows.size();
  return std::move(table.log);
}

}  // namespace tpf::offline
