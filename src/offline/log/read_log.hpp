// Reading tpf logs (docs/log-format.md; implementation notes in docs/log-format-notes.md).
#pragma once

#include <filesystem>

#include "offline/log/log.hpp"

namespace tpf::offline {

/// Reads a tpf log: '#' metadata, a header line, then comma-separated decimal numbers.
/// - column order is free; unknown columns are kept; a 't' column is required;
/// - an empty field or 'nan' is a missing value: NaN in `values`, counted in `quality`;
/// - gaps (dt > 1.5 / rate, rate from 'rate_hz' or else the median dt) are counted in `quality`;
/// - errors name file, line and column: a 'tpf-log' major version > 1, a wrong field count, text
///   where a number belongs, an infinite value, a line cut off at the end of the file, a missing
///   or non-increasing t.
/// Reads the file with one read and parses it on two threads.
Log read_log(const std::filesystem::path& path);

}  // namespace tpf::offline
