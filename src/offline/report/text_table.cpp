#include "offline/report/text_table.hpp"

#include <algorithm>
#include <cctype>
#include <vector>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/report/text_format.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::offline {
namespace {

/// Starts with a digit, a sign or the typographic minus: right-aligned.
bool numeric(const std::string& cell) {
  return !cell.empty() && (std::isdigit(static_cast<unsigned char>(cell[0])) || cell[0] == '-' ||
                           cell[0] == '+' || cell.rfind("\u2212", 0) == 0);
}

}  // namespace

std::string table_text(const Table& table, int indent) {
  std::vector<std::size_t> width(table.header.size(), 0);
  const auto widen = [&](const std::vector<std::string>& row) {
    for (std::size_t c = 0; c < row.size() && c < width.size(); ++c)
      width[c] = std::max(width[c], utf8_characters(row[c]));
  };
  widen(table.header);
  for (const auto& row : table.rows)
    widen(row);
  const auto line = [&](const std::vector<std::string>& row) {
    std::string text(static_cast<std::size_t>(indent), ' ');
    for (std::size_t c = 0; c < row.size() && c < width.size(); ++c) {
      const std::string pad(width[c] - utf8_characters(row[c]), ' ');
      const bool last = c + 1 == row.size();
      text += c ? "  " : "";
      text += numeric(row[c]) ? pad + row[c] : row[c] + (last ? "" : pad);
    }
    return text + "\n";
  };
  std::string text = line(table.header);
  for (const auto& row : table.rows)
    text += line(row);
  return text;
}

}  // namespace tpf::offline

TPF_UNOPTIMISED_WHEN_SANITIZED_END
