// Start-up loading of friction parameter files (see include/tpf/friction/friction_file.hpp).
#include "tpf/friction/friction_file.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "tpf/common/error.hpp"

namespace tpf {
namespace {

using nlohmann::json;

const std::set<std::string> kStribeckKeys = {
    "effort_unit", "coulomb",      "static",       "stribeck_velocity", "stribeck_exponent",
    "viscous",     "load_coulomb", "load_viscous", "description"};
const std::set<std::string> kLuGreKeys = {"bristle_stiffness", "bristle_damping"};

json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error::at(path, 0, "", "cannot open friction parameter file");
  try {
    json j = json::parse(in);
    if (!j.is_object()) throw Error::at(path, 0, "", "top level must be a JSON object");
    for (const auto& [key, value] : j.items()) {
      if (!kStribeckKeys.count(key) && !kLuGreKeys.count(key))
        throw Error::at(path, 0, key, "unknown key");
    }
    const std::string unit = j.value("effort_unit", std::string("N*m"));
    if (unit != "N*m" && unit != "mA")
      throw Error::at(path, 0, "effort_unit", "must be \"N*m\" or \"mA\", got \"" + unit + "\"");
    return j;
  } catch (const json::exception& e) {
    throw Error::at(path, 0, "", std::string("invalid JSON: ") + e.what());
  }
}

enum class Bound { kNonNegative, kPositive };

// Fills `out` from the array `key`; a missing optional key leaves the default in place.
template <typename S, int N>
void read_vector(const json& j, const std::string& path, const std::string& key, Bound bound,
                 bool required, JointVector<S, N>& out) {
  if (!j.contains(key)) {
    if (required) throw Error::at(path, 0, key, "missing");
    return;
  }
  const json& a = j.at(key);
  if (!a.is_array() || a.size() != static_cast<std::size_t>(N))
    throw Error::at(path, 0, key, "must be an array of " + std::to_string(N) + " numbers");
  for (int i = 0; i < N; ++i) {
    if (!a[i].is_number())
      throw Error::at(path, 0, key + "[" + std::to_string(i) + "]", "must be a number");
    const double v = a[i].get<double>();
    const bool ok = std::isfinite(v) && (bound == Bound::kPositive ? v > 0.0 : v >= 0.0);
    if (!ok)
      throw Error::at(path, 0, key + "[" + std::to_string(i) + "]",
                      std::string("must be ") +
                          (bound == Bound::kPositive ? "positive" : "non-negative") + ", got " +
                          std::to_string(v));
    out[i] = static_cast<S>(v);
  }
}

template <typename S, int N>
StribeckParameters<S, N> parse_stribeck(const json& j, const std::string& path) {
  StribeckParameters<S, N> p;
  read_vector<S, N>(j, path, "coulomb", Bound::kNonNegative, true, p.coulomb);
  read_vector<S, N>(j, path, "static", Bound::kNonNegative, true, p.static_friction);
  read_vector<S, N>(j, path, "stribeck_velocity", Bound::kPositive, true, p.stribeck_velocity);
  read_vector<S, N>(j, path, "stribeck_exponent", Bound::kPositive, true, p.stribeck_exponent);
  read_vector<S, N>(j, path, "viscous", Bound::kNonNegative, true, p.viscous);
  read_vector<S, N>(j, path, "load_coulomb", Bound::kNonNegative, false, p.load_coulomb);
  read_vector<S, N>(j, path, "load_viscous", Bound::kNonNegative, false, p.load_viscous);
  return p;
}

}  // namespace

template <typename S, int N>
StribeckParameters<S, N> load_stribeck_parameters(const std::string& path) {
  const json j = read_json(path);
  LuGreParameters<S, N> unused;
  read_vector<S, N>(j, path, "bristle_stiffness", Bound::kPositive, false,
                    unused.bristle_stiffness);
  read_vector<S, N>(j, path, "bristle_damping", Bound::kNonNegative, false, unused.bristle_damping);
  return parse_stribeck<S, N>(j, path);
}

template <typename S, int N>
LuGreParameters<S, N> load_lugre_parameters(const std::string& path) {
  const json j = read_json(path);
  LuGreParameters<S, N> p;
  p.stribeck = parse_stribeck<S, N>(j, path);
  read_vector<S, N>(j, path, "bristle_stiffness", Bound::kPositive, true, p.bristle_stiffness);
  read_vector<S, N>(j, path, "bristle_damping", Bound::kNonNegative, true, p.bristle_damping);
  return p;
}

std::string friction_effort_unit(const std::string& path) {
  return read_json(path).value("effort_unit", std::string("N*m"));
}

#define TPF_INSTANTIATE_FRICTION_FILE(N)                                                          \
  template StribeckParameters<double, N> load_stribeck_parameters<double, N>(const std::string&); \
  template LuGreParameters<double, N> load_lugre_parameters<double, N>(const std::string&);
TPF_INSTANTIATE_FRICTION_FILE(1)
TPF_INSTANTIATE_FRICTION_FILE(2)
TPF_INSTANTIATE_FRICTION_FILE(3)
TPF_INSTANTIATE_FRICTION_FILE(4)
TPF_INSTANTIATE_FRICTION_FILE(5)
TPF_INSTANTIATE_FRICTION_FILE(6)
TPF_INSTANTIATE_FRICTION_FILE(7)
#undef TPF_INSTANTIATE_FRICTION_FILE

}  // namespace tpf
