// Start-up helpers for reading the project's JSON files (robot, pads, parameters, weights) with
// errors that name the file and the field. Not for the per-cycle path.
#pragma once

#include <filesystem>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>

#include "tpf/common/types.hpp"

namespace tpf::json {

/// Parses a JSON file; tpf::Error names the file, line and column of a syntax error. Nesting
/// deeper than 64 levels is refused (every tpf file needs fewer than 5).
nlohmann::json read_file(const std::filesystem::path& path);
/// Throws the tpf::Error for a file nlohmann::json could not parse: "file:line: not valid JSON:
/// <what>". `byte` is parse_error::byte (1-based offset of the error), or 0 for other parse
/// exceptions (e.g. out_of_range 406, a number like 1e999 too large for a double), whose line is
/// that of the token quoted in `what`.
[[noreturn]] void fail_unparsable(const std::filesystem::path& path, std::size_t byte,
                                  std::string_view what);

/// Checks `"format": <format>` and `"version": <= max_version`.
void check_format(const nlohmann::json& j, const std::string& file, std::string_view format,
                  int max_version);

/// The member `key` of object `j` (at JSON path `where`), or tpf::Error "file: where.key: missing".
const nlohmann::json& member(const nlohmann::json& j, const std::string& file,
                             const std::string& where, const std::string& key);

/// A finite number; the error names the field.
double number(const nlohmann::json& j, const std::string& file, const std::string& where,
              const std::string& key);

/// A string field.
std::string string(const nlohmann::json& j, const std::string& file, const std::string& where,
                   const std::string& key);

/// A 3-vector of finite numbers.
Vector3<double> vector3(const nlohmann::json& j, const std::string& file, const std::string& where,
                        const std::string& key);

/// Refuses any member of object `j` not in `allowed` (a typo must not be silently ignored).
void only_keys(const nlohmann::json& j, const std::string& file, const std::string& where,
               std::initializer_list<std::string_view> allowed);

}  // namespace tpf::json
