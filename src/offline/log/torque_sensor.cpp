#include "offline/log/torque_sensor.hpp"

#include <cmath>
#include <cstdio>

namespace tpf::offline {
namespace {

SensorColumn sensor_column(const Log& log, int column, Eigen::Index begin, Eigen::Index end) {
  SensorColumn s;
  if (column < 0) return s;
  bool any = false;
  for (Eigen::Index r = begin; r < end; ++r) {
    const double v = log.values(r, column);
    if (std::isnan(v)) continue;
    s.min = any ? std::min(s.min, v) : v;
    s.max = any ? std::max(s.max, v) : v;
    any = true;
  }
  if (any) s.state = s.max - s.min < kFlatSensorRange ? SensorState::Flat : SensorState::Varies;
  return s;
}

/// "1-3, 5" for the 1-based joints in `joints`.
std::string joint_ranges(const std::vector<int>& joints) {
  std::string text;
  for (std::size_t i = 0; i < joints.size();) {
    std::size_t k = i;
    while (k + 1 < joints.size() && joints[k + 1] == joints[k] + 1)
      ++k;
    text.append(text.empty() ? "" : ", ").append(std::to_string(joints[i]));
    if (k > i) text.append("-").append(std::to_string(joints[k]));
    i = k + 1;
  }
  return text;
}

/// Whether the log has a tau_sensor<j> column for any of its joints.
bool has_torque_sensor(const Log& log, int joints) {
  for (int j = 1; j <= joints; ++j)
    if (log.has(indexed_name("tau_sensor", j))) return true;
  return false;
}

}  // namespace

std::vector<std::vector<SensorColumn>> torque_sensor_columns(const Log& log, int joints) {
  std::vector<std::vector<SensorColumn>> out(log.file_count());
  for (std::size_t f = 0; f < log.file_count(); ++f) {
    const auto [begin, end] = log.file_rows(f);
    for (int j = 1; j <= joints; ++j)
      out[f].push_back(sensor_column(log, log.column(indexed_name("tau_sensor", j)), begin, end));
  }
  return out;
}

std::vector<std::string> torque_sensor_report(const Log& log, int joints) {
  if (!has_torque_sensor(log, joints)) return {"torque sensor: none (no tau_sensor<j> column)"};
  return torque_sensor_problems(log, joints);
}

std::vector<std::string> torque_sensor_problems(const Log& log, int joints) {
  if (!has_torque_sensor(log, joints)) return {};
  const auto columns = torque_sensor_columns(log, joints);
  std::vector<std::string> lines;
  for (std::size_t f = 0; f < columns.size(); ++f) {
    std::vector<int> missing, flat;
    std::string values;
    for (int j = 0; j < joints; ++j) {
      const SensorColumn& c = columns[f][static_cast<std::size_t>(j)];
      if (c.state == SensorState::Missing) missing.push_back(j + 1);
      if (c.state != SensorState::Flat) continue;
      flat.push_back(j + 1);
      char v[64];
      std::snprintf(v, sizeof v, "%sj%d %.3g", values.empty() ? "" : ", ", j + 1,
                    0.5 * (c.min + c.max));
      values += v;
    }
    if (missing.empty() && flat.empty()) continue;
    std::string line = "torque sensor, ";
    line.append(log.file_path(f)).append(":");
    if (!missing.empty())
      line.append(" missing on joints ").append(joint_ranges(missing)).append(";");
    if (!flat.empty())
      line.append(" flat (range < 0.05 N*m) on joints ")
          .append(joint_ranges(flat))
          .append(" (")
          .append(values)
          .append(" N*m)");
    if (line.back() == ';') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

}  // namespace tpf::offline
