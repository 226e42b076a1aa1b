// Parsing a JSON file for the start-up loaders, with errors that name the file and the line.
#pragma once

#include <filesystem>
#include <nlohmann/json_fwd.hpp>

namespace tpf::json {

/// Parses the JSON file `path`. Throws tpf::Error "file:line: not valid JSON: <reason>" on a
/// syntax error or a number beyond the double range (1e999), "file: cannot open the file", and
/// "file:line: nested deeper than 64 levels" (tpf's files need fewer than 5; deeper values would
/// overflow the stack when copied or printed).
nlohmann::json parse_file(const std::filesystem::path& path);

}  // namespace tpf::json
