// The joint torque sensor columns tau_sensor<j> of a log (docs/log-format.md): where they are
// missing, flat or usable, per file and joint. A sensor is a measured reference to score
// against, never an input to a run-time estimate.
#pragma once

#include <string>
#include <vector>

#include "offline/log/log.hpp"

namespace tpf::offline {

/// What one joint's sensor column holds over one file of a log.
enum class SensorState {
  Missing,  ///< no tau_sensor<j> column, or every value missing
  Flat,     ///< max − min below kFlatSensorRange: dead, zeroed, or never loaded in this file
  Varies,   ///< usable as a reference
};

/// A sensor whose readings span less than this [N·m] over a file is flat.
inline constexpr double kFlatSensorRange = 0.05;

struct SensorColumn {
  SensorState state = SensorState::Missing;
  double min = 0.0, max = 0.0;  ///< over the finite values [N·m]
};

/// [file][joint] states of tau_sensor1..tau_sensorN over each file of `log` (Log::file_starts).
std::vector<std::vector<SensorColumn>> torque_sensor_columns(const Log& log, int joints);

/// True when joint j's (0-based) sensor varies in file f.
inline bool sensor_usable(const std::vector<std::vector<SensorColumn>>& c, std::size_t f, int j) {
  return c[f][static_cast<std::size_t>(j)].state == SensorState::Varies;
}

/// Lines for the terminal: "torque sensor: none (no tau_sensor<j> column)", or one line per
/// file naming the joints whose sensor is missing or flat (with its constant value), e.g.
/// "torque sensor, Trajectory1.csv.gz: flat on joints 1-7 (0 N·m)". Empty when every sensor
/// varies in every file.
std::vector<std::string> torque_sensor_report(const Log& log, int joints);

/// The lines of torque_sensor_report that name a missing or flat sensor: nothing for a log
/// without any tau_sensor<j> column (a fitting command has nothing to say about it).
std::vector<std::string> torque_sensor_problems(const Log& log, int joints);

}  // namespace tpf::offline
