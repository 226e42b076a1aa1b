// Text pieces of the log format shared by the reader and the writers (internal to offline/log).
#pragma once

#include <charconv>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "offline/log/log_metadata.hpp"

namespace tpf::offline::log_text {

/// Longest text to_chars produces for a double in shortest round-trip form, plus margin.
inline constexpr int kMaxNumberChars = 32;

/// Appends `value` in the shortest form that reads back to the same double ('nan' for NaN).
/// Precondition: value is finite or NaN.
inline void append_number(std::string& out, double value) {
  if (std::isnan(value)) {
    out += "nan";
    return;
  }
  char buffer[kMaxNumberChars];
  const auto result = std::to_chars(buffer, buffer + kMaxNumberChars, value);
  out.append(buffer, result.ptr);
}

/// `value` through a printf pattern of one number ("%.6g"): the numbers of the import's and the
/// checks' messages.
inline std::string printed(const char* pattern, double value) {
  char text[96];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

/// Appends one data line: values separated by ',' and a final '\n'.
inline void append_row(std::string& out, std::span<const double> row) {
  for (std::size_t c = 0; c < row.size(); ++c) {
    if (c) out += ',';
    append_number(out, row[c]);
  }
  out += '\n';
}

/// The metadata lines and the header line: "# tpf-log: 1" first, then the other entries in order.
/// Throws tpf::Error on names the format cannot hold (empty, duplicate, ',' or line breaks).
std::string prelude(const LogMetadata& meta, const std::vector<std::string>& columns,
                    std::string_view path);

/// Throws tpf::Error naming the column when `row` holds an infinite value.
void check_finite(std::span<const double> row, const std::vector<std::string>& columns,
                  std::string_view path);

}  // namespace tpf::offline::log_text
