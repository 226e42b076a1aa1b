// A report table as fixed-width text for a terminal: columns padded to their widest cell.
#pragma once

#include <string>

#include "offline/report/html_report.hpp"

namespace tpf::offline {

/// `table` as lines of text: the header, then one line per row, columns separated by two spaces,
/// numeric-looking cells right-aligned, widths counted in characters (UTF-8); indented by
/// `indent` spaces. The caption is not printed.
std::string table_text(const Table& table, int indent = 2);

}  // namespace tpf::offline
