#include "offline/log/log_text.hpp"

#include <set>

#include "tpf/common/error.hpp"

namespace tpf::offline::log_text {
namespace {

bool has_line_break(std::string_view s) {
  return s.find_first_of("\r\n") != std::string_view::npos;
}

}  // namespace

std::string prelude(const LogMetadata& meta, const std::vector<std::string>& columns,
                    std::string_view path) {
  std::string text = "# tpf-log: 1\n";
  for (const auto& [key, value] : meta.entries) {
    if (key == "tpf-log") continue;
    if (has_line_break(key) || has_line_break(value) || key.find(':') != std::string::npos)
      throw Error::at(path, 0, "metadata", "entry '" + key + "' cannot be written on one line");
    // A line without a key is read back as one when its text holds no ':' before which a key
    // would be read; otherwise it is written after an empty key ("# : text").
    const bool keyless_needs_colon = key.empty() && value.find(':') != std::string::npos;
    text += key.empty() ? (keyless_needs_colon ? "# : " : "# ") + value + "\n"
                        : "# " + key + ": " + value + "\n";
  }
  std::set<std::string_view> seen;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const std::string& name = columns[c];
    if (name.empty() || name.find_first_of(",# \t\r\n") != std::string::npos)
      throw Error::at(path, 0, "column " + std::to_string(c + 1),
                      "name '" + name + "' is empty or holds ',', '#', a space or a line break");
    if (!seen.insert(name).second) throw Error::at(path, 0, name, "column name appears twice");
    if (c) text += ',';
    text += name;
  }
  if (columns.empty()) throw Error::at(path, 0, "", "a log needs at least one column");
  text += '\n';
  return text;
}

void check_finite(std::span<const double> row, const std::vector<std::string>& columns,
                  std::string_view path) {
  for (std::size_t c = 0; c < row.size(); ++c)
    if (std::isinf(row[c]))
      throw Error::at(path, 0, columns[c], "cannot write an infinite value (use NaN for missing)");
}

}  // namespace tpf::offline::log_text
