#include "tpf/common/json_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "tpf/common/error.hpp"

namespace tpf::json {
namespace {

constexpr int kMaxDepth = 64;

/// "file:line: nested deeper than 64 levels", the line where the 65th level opens.
[[noreturn]] void fail_too_deep(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  long line = 1;
  int depth = 0;
  bool in_string = false, escaped = false;
  for (char c; in.get(c) && depth <= kMaxDepth;) {
    if (c == '\n') ++line;
    if (in_string) {
      escaped = !escaped && c == '\\';
      if (c == '"' && !escaped) in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  throw Error::at(path.string(), line, "",
                  "nested deeper than " + std::to_string(kMaxDepth) + " levels");
}

}  // namespace

nlohmann::json read_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path);
  if (!in) throw Error::at(file, 0, "", "cannot open the file");
  // Nesting is bounded: copying, printing or comparing a json value recurses once per level, so
  // a file of 100 000 '[' would overflow the stack long after parsing succeeded.
  const auto bounded_depth = [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > kMaxDepth) fail_too_deep(path);
    return true;
  };
  try {
    return nlohmann::json::parse(in, bounded_depth);
  } catch (const nlohmann::json::parse_error& e) {
    fail_unparsable(path, e.byte, e.what());
  } catch (const nlohmann::json::exception& e) {  // e.g. a number too large for a double
    fail_unparsable(path, 0, e.what());
  }
}

void fail_unparsable(const std::filesystem::path& path, std::size_t byte, std::string_view what) {
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (byte == 0) {  // no offset: find the token the message quotes, e.g. "parsing '1e999'"
    const std::size_t open = what.find('\'');
    const std::size_t close = open == std::string_view::npos ? open : what.find('\'', open + 1);
    if (close != std::string_view::npos) {
      const std::size_t at = text.find(what.substr(open + 1, close - open - 1));
      if (at != std::string::npos) byte = at + 1;
    }
  }
  const long line = byte == 0 ? 0
                              : 1 + std::count(text.begin(),
                                               text.begin() + static_cast<std::ptrdiff_t>(
                                                                  std::min(byte - 1, text.size())),
                                               '\n');
  throw Error::at(path.string(), line, "", std::string("not valid JSON: ").append(what));
}

void check_format(const nlohmann::json& j, const std::string& file, std::string_view format,
                  int max_version) {
  if (!j.is_object()) throw Error::at(file, 0, "", "the top level must be a JSON object");
  const std::string got = string(j, file, "", "format");
  if (got != format)
    throw Error::at(file, 0, "format", "is '" + got + "', expected '" + std::string(format) + "'");
  const double version = number(j, file, "", "version");
  if (version > max_version)
    throw Error::at(file, 0, "version",
                    "is " + j.at("version").dump() + "; this tpf reads up to version " +
                        std::to_string(max_version));
}

const nlohmann::json& member(const nlohmann::json& j, const std::string& file,
                             const std::string& where, const std::string& key) {
  const std::string field = where.empty() ? key : where + "." + key;
  if (!j.is_object() || !j.contains(key)) throw Error::at(file, 0, field, "missing");
  return j.at(key);
}

double number(const nlohmann::json& j, const std::string& file, const std::string& where,
              const std::string& key) {
  const nlohmann::json& v = member(j, file, where, key);
  const std::string field = where.empty() ? key : where + "." + key;
  if (!v.is_number()) throw Error::at(file, 0, field, "must be a number, got " + v.dump());
  const double x = v.get<double>();
  if (!std::isfinite(x)) throw Error::at(file, 0, field, "must be finite");
  return x;
}

std::string string(const nlohmann::json& j, const std::string& file, const std::string& where,
                   const std::string& key) {
  const nlohmann::json& v = member(j, file, where, key);
  if (!v.is_string())
    throw Error::at(file, 0, where.empty() ? key : where + "." + key, "must be a string");
  return v.get<std::string>();
}

Vector3<double> vector3(const nlohmann::json& j, const std::string& file, const std::string& where,
                        const std::string& key) {
  const nlohmann::json& v = member(j, file, where, key);
  const std::string field = where.empty() ? key : where + "." + key;
  if (!v.is_array() || v.size() != 3) throw Error::at(file, 0, field, "must be [x, y, z]");
  Vector3<double> out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      throw Error::at(file, 0, field, "must hold three finite numbers");
    out(i) = v[i].get<double>();
  }
  return out;
}

void only_keys(const nlohmann::json& j, const std::string& file, const std::string& where,
               std::initializer_list<std::string_view> allowed) {
  for (const auto& [key, value] : j.items()) {
    bool known = false;
    for (std::string_view a : allowed)
      known = known || a == key;
    if (!known) {
      std::string list;
      for (std::string_view a : allowed)
        list += (list.empty() ? "" : ", ") + std::string(a);
      throw Error::at(file, 0, where.empty() ? key : where + "." + key,
                      "unknown key (expected one of: " + list + ")");
    }
  }
}

}  // namespace tpf::json
