#include "tpf/common/json_file.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tpf/common/error.hpp"

namespace tpf::json {

nlohmann::json read_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path);
  if (!in) throw Error::at(file, 0, "", "cannot open the file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the offset of the error; turn it into a line number.
    std::ifstream again(path);
    long line = 1;
    char c;
    for (std::size_t i = 1; i < e.byte && again.get(c); ++i)
      if (c == '\n') ++line;
    throw Error::at(file, line, "", std::string("not valid JSON: ") + e.what());
  }
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
                    "is " + std::to_string(static_cast<int>(version)) +
                        "; this tpf reads up to version " + std::to_string(max_version));
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
