#include "offline/log/import_map.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/common/json_object.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// Accepted units per tpf prefix, with the factor to the log format's unit.
struct UnitChoice {
  const char* name;
  double scale;
};

std::vector<UnitChoice> units_of(const std::string& prefix) {
  constexpr double deg = std::numbers::pi / 180.0;
  if (prefix == "q") return {{"rad", 1.0}, {"deg", deg}, {"m", 1.0}, {"mm", 1e-3}};
  if (prefix == "dq") return {{"rad/s", 1.0}, {"deg/s", deg}, {"m/s", 1.0}, {"mm/s", 1e-3}};
  if (prefix == "ddq")
    return {{"rad/s^2", 1.0}, {"deg/s^2", deg}, {"m/s^2", 1.0}, {"mm/s^2", 1e-3}};
  if (prefix == "i") return {{"mA", 1.0}, {"A", 1000.0}};
  if (prefix == "temp") return {{"degC", 1.0}};
  // tau, tau_sensor, tau_maker; N for a prismatic joint's force
  return {{"N*m", 1.0}, {"N.m", 1.0}, {"Nm", 1.0}, {"mN*m", 1e-3}, {"N", 1.0}};
}

double unit_factor(json::Object& c, const std::string& prefix, const std::string& unit,
                   const std::string& key) {
  const auto choices = units_of(prefix);
  const auto it = std::find_if(choices.begin(), choices.end(),
                               [&](const UnitChoice& u) { return unit == u.name; });
  if (it == choices.end()) {
    std::string accepted;
    for (const UnitChoice& u : choices)
      accepted.append(accepted.empty() ? "" : ", ").append(u.name);
    c.fail(key, "'" + unit + "' is not one of " + accepted);
  }
  return it->scale;
}

/// A key holding one number for every joint or an array of one per joint; `fallback` if absent.
std::vector<double> per_joint(json::Object& c, const std::string& key, double fallback, double lo,
                              double hi, int joints) {
  const auto n = static_cast<std::size_t>(joints);
  if (c.is_array(key)) return c.numbers(key, lo, hi, n);
  return std::vector<double>(n, c.number(key, fallback, lo, hi));
}

void read_units(json::Object& c, ImportColumn& column, int joints) {
  const auto n = static_cast<std::size_t>(joints);
  column.unit =
      c.is_array("unit") ? c.texts("unit", n) : std::vector<std::string>(n, c.text("unit"));
  for (std::size_t k = 0; k < n; ++k)
    column.unit_factor.push_back(
        unit_factor(c, column.prefix, column.unit[k],
                    c.is_array("unit") ? "unit[" + std::to_string(k) + "]" : std::string("unit")));
}

/// scale, sign (±1), offset, side and, for a current, the motor torque constants.
void read_scaling(json::Object& c, ImportColumn& column, int joints) {
  constexpr double inf = json::Object::kInfinity;
  column.scale = per_joint(c, "scale", 1.0, -inf, inf, joints);
  const std::vector<double> sign = per_joint(c, "sign", 1.0, -1.0, 1.0, joints);
  for (std::size_t k = 0; k < sign.size(); ++k) {
    if (sign[k] != 1.0 && sign[k] != -1.0) c.fail("sign", "must be 1 or -1 (per joint)");
    column.scale[k] *= sign[k];
  }
  column.offset = per_joint(c, "offset", 0.0, -inf, inf, joints);
  const bool can_be_motor = column.prefix == "q" || column.prefix == "dq" ||
                            column.prefix == "ddq" || column.prefix == "i" ||
                            column.prefix == "tau";
  if (can_be_motor)
    column.side =
        c.choice("side", "joint", {"joint", "motor"}) == "motor" ? Side::Motor : Side::Joint;
  if (column.prefix != "i") return;
  if (c.has("torque_constant"))
    column.torque_constant = per_joint(c, "torque_constant", 0.0, -inf, inf, joints);
  for (const double kt : column.torque_constant)
    if (kt == 0.0) c.fail("torque_constant", "must not be 0");
  if (column.side == Side::Motor && column.torque_constant.empty())
    c.fail("torque_constant",
           "missing: a motor-side current reaches the joint through the motor's torque constant "
           "(N*m/A, signed) and the transmission");
  column.write_torque = c.choice("write", "current", {"current", "torque"}) == "torque";
  if (column.write_torque && column.torque_constant.empty())
    c.fail("write", "'torque' needs torque_constant");
}

/// "transmission": {"ratio": [...], "coupling": [[...], ...]}: R = diag(ratio)·coupling.
void read_transmission(json::Object& root, ImportMap& map) {
  const auto n = static_cast<std::size_t>(map.joints);
  map.transmission = Eigen::MatrixXd::Identity(map.joints, map.joints);
  if (!root.has("transmission")) return;
  auto tr = root.child("transmission");
  const std::vector<double> ratio =
      tr.numbers("ratio", -json::Object::kInfinity, json::Object::kInfinity, n);
  Eigen::MatrixXd coupling = Eigen::MatrixXd::Identity(map.joints, map.joints);
  if (tr.has("coupling")) {
    const auto rows = tr.number_rows("coupling", n, n);
    for (std::size_t r = 0; r < n; ++r)
      for (std::size_t c = 0; c < n; ++c)
        coupling(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = rows[r][c];
  }
  tr.finish();
  for (std::size_t k = 0; k < n; ++k)
    if (ratio[k] == 0.0) tr.fail("ratio", "must not hold 0 (a motor that does not rotate)");
  map.transmission = Eigen::VectorXd::Map(ratio.data(), map.joints).asDiagonal() * coupling;
  map.coupled = !coupling.isDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(map.transmission);
  const Eigen::VectorXd sv = svd.singularValues();
  if (!(sv[sv.size() - 1] > 1e-9 * sv[0]))
    tr.fail("coupling",
            "diag(ratio)·coupling is singular: the joints cannot be told from the "
            "motors");
}

constexpr const char* kPrefixes[] = {"q",   "dq",         "ddq",       "i",
                                     "tau", "tau_sensor", "tau_maker", "temp"};

}  // namespace

bool ImportMap::has(const std::string& prefix) const {
  return std::any_of(columns.begin(), columns.end(),
                     [&](const ImportColumn& c) { return c.prefix == prefix; });
}

const ImportColumn& ImportMap::column(const std::string& prefix) const {
  for (const ImportColumn& c : columns)
    if (c.prefix == prefix) return c;
  throw Error(file + ": columns: no '" + prefix + "'");
}

std::string ImportMap::source_name(const ImportColumn& column, int k) const {
  if (!column.sources.empty()) return column.sources[static_cast<std::size_t>(k - 1)];
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

  map.files = root.has("files") ? root.integer("files", 1, 64) : 1;
  map.join =
      root.choice("join", "index", {"index", "time"}) == "index" ? JoinRule::Index : JoinRule::Time;
  auto time = root.child("time");
  if (!root.has("time"))
    root.fail("time", "missing (the time column and its unit, or {\"unit\": \"rate\"})");
  const std::string unit = time.choice("unit", "s", {"s", "ms", "us", "sample", "rate"});
  if (unit != "rate") map.time_column = time.text("column");
  map.time_unit = unit == "s"        ? TimeUnit::Seconds
                  : unit == "ms"     ? TimeUnit::Milliseconds
                  : unit == "us"     ? TimeUnit::Microseconds
                  : unit == "sample" ? TimeUnit::SampleIndex
                                     : TimeUnit::Rate;
  if (unit == "rate" && map.rate_hz == 0.0)
    root.fail("rate_hz", "required when the time comes from the rate (no time column)");
  if (map.join == JoinRule::Time && map.time_column.empty())
    root.fail("join", "'time' needs a time column in every file");
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
    if (c.is_array("source"))
      column.sources = c.texts("source", static_cast<std::size_t>(map.joints));
    else
      column.source = c.text("source");
    if (column.sources.empty() && map.joints > 1 && column.source.find("{j}") == std::string::npos)
      c.fail("source", "'" + column.source +
                           "' needs {j} where the joint number goes (the map has " +
                           std::to_string(map.joints) +
                           " joints; only a 1-joint map may name its column without {j}; or "
                           "give an array of one name per joint)");
    read_units(c, column, map.joints);
    read_scaling(c, column, map.joints);
    c.finish();
    map.columns.push_back(column);
  }
  columns.finish();
  read_transmission(root, map);
  if (root.has("derive")) {
    auto derive = root.child("derive");
    map.derive_cutoff_hz = derive.number("cutoff_hz", kDefaultDeriveCutoffHz, 1e-6, 1e9);
    derive.finish();
  }
  const auto has = [&](const char* prefix) { return map.has(prefix); };
  if (!has("q")) root.fail("columns", "needs q");
  if (!has("dq") && map.derive_cutoff_hz == 0.0)
    root.fail("columns", "needs dq, or a \"derive\": {\"cutoff_hz\": ...} to derive it from q");
  if (map.coupled)
    for (const ImportColumn& c : map.columns)
      if (c.prefix == "i" && c.side == Side::Motor && !c.write_torque)
        root.fail("columns",
                  "i: motor currents of a coupled transmission are no joint's "
                  "current: give \"write\": \"torque\" (tau<j> = Rᵀ·K_t·i)");
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
