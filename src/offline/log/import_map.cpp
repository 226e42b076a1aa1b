#include "offline/log/import_map.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tpf/common/error.hpp"
#include "tpf/common/json_object.hpp"

namespace tpf::offline {
namespace {

/// Accepted units per tpf prefix, with the factor to the log format's unit.
struct UnitChoice {
  const char* name;
  double scale;
};

std::vector<UnitChoice> units_of(const std::string& prefix) {
  constexpr double deg = std::numbers::pi / 180.0;
  if (prefix == "q") return {{"rad", 1.0}, {"deg", deg}};
  if (prefix == "dq") return {{"rad/s", 1.0}, {"deg/s", deg}};
  if (prefix == "ddq") return {{"rad/s^2", 1.0}, {"deg/s^2", deg}};
  if (prefix == "i") return {{"mA", 1.0}, {"A", 1000.0}};
  if (prefix == "temp") return {{"degC", 1.0}};
  return {{"N*m", 1.0}, {"N.m", 1.0}, {"Nm", 1.0}};  // tau, tau_sensor, tau_maker
}

constexpr const char* kPrefixes[] = {"q",   "dq",         "ddq",       "i",
                                     "tau", "tau_sensor", "tau_maker", "temp"};

}  // namespace

std::string ImportMap::source_name(const ImportColumn& column, int k) const {
  std::string name = column.source;
  const std::size_t at = name.find("{j}");
  if (at == std::string::npos) return name;  // a 1-joint map's column of its one joint
  return name.replace(at, 3, std::to_string(joint_order[static_cast<std::size_t>(k - 1)]));
}

ImportMap load_import_map(const std::filesystem::path& path) {
  auto root = json::Object::read_document(path, "tpf-import", 1);
  ImportMap map;
  map.file = path.string();
  map.joints = root.integer("joints", 1, 64);
  std::vector<double> order(static_cast<std::size_t>(map.joints));
  for (int k = 0; k < map.joints; ++k)
    order[static_cast<std::size_t>(k)] = k + 1;
  order = root.numbers("joint_order", order, 0, 1e6, static_cast<std::size_t>(map.joints));
  for (const double k : order) {
    if (k != std::floor(k) || k < 0) root.fail("joint_order", "must hold whole numbers");
    map.joint_order.push_back(static_cast<int>(k));
  }
  std::vector<int> sorted = map.joint_order;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    root.fail("joint_order", "names a source joint twice");
  map.rate_hz = root.number("rate_hz", 0.0, 0.0, 1e9);

  auto time = root.child("time");
  if (!root.has("time")) root.fail("time", "missing (the time column and its unit)");
  map.time_column = time.text("column");
  const std::string unit = time.choice("unit", "s", {"s", "ms", "us", "sample"});
  map.time_unit = unit == "s"    ? TimeUnit::Seconds
                  : unit == "ms" ? TimeUnit::Milliseconds
                  : unit == "us" ? TimeUnit::Microseconds
                                 : TimeUnit::SampleIndex;
  map.timestamps = time.choice("rule", "keep", {"keep", "regular"}) == "keep"
                       ? TimestampRule::Keep
                       : TimestampRule::Regular;
  time.finish();
  if (map.rate_hz == 0.0 && map.time_unit == TimeUnit::SampleIndex)
    root.fail("rate_hz", "required when time is a sample index");
  if (map.rate_hz == 0.0 && map.timestamps == TimestampRule::Regular)
    root.fail("rate_hz", "required by the time rule 'regular'");

  auto columns = root.child("columns");
  for (const char* prefix : kPrefixes) {
    if (!columns.has(prefix)) continue;
    auto c = columns.child(prefix);
    ImportColumn column;
    column.prefix = prefix;
    column.source = c.text("source");
    if (map.joints > 1 && column.source.find("{j}") == std::string::npos)
      c.fail("source", "'" + column.source +
                           "' needs {j} where the joint number goes (the map has " +
                           std::to_string(map.joints) +
                           " joints; only a 1-joint map may name its column without {j})");
    column.unit = c.text("unit");
    const auto choices = units_of(prefix);
    const auto it = std::find_if(choices.begin(), choices.end(),
                                 [&](const UnitChoice& u) { return column.unit == u.name; });
    if (it == choices.end()) {
      std::string accepted;
      for (const UnitChoice& u : choices)
        accepted.append(accepted.empty() ? "" : ", ").append(u.name);
      c.fail("unit", "'" + column.unit + "' is not one of " + accepted);
    }
    column.scale = it->scale;
    c.finish();
    map.columns.push_back(column);
  }
  columns.finish();
  const auto has = [&](const char* prefix) {
    return std::any_of(map.columns.begin(), map.columns.end(),
                       [&](const ImportColumn& c) { return c.prefix == prefix; });
  };
  if (!has("q") || !has("dq")) root.fail("columns", "needs q and dq");
  if (!has("i") && !has("tau")) root.fail("columns", "needs an effort: i (current) or tau");
  if (has("i") && has("tau"))
    root.fail("columns",
              "maps both i and tau: a log has one effort (the tools would read i and "
              "never tau); keep the one the identification should fit");

  if (root.has("metadata")) {
    auto meta = root.child("metadata");
    for (const char* key : {"robot", "note", "source", "license"})
      if (meta.has(key)) map.metadata.emplace_back(key, meta.text(key));
    meta.finish();
  }
  root.finish();
  return map;
}

}  // namespace tpf::offline
