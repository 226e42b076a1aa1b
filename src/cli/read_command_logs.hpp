// The logs a fitting command (identify, diagnose) reads: several files as one log, with what was
// joined and where the torque sensors are flat or missing said once.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "offline/log/read_logs.hpp"
#include "offline/log/torque_sensor.hpp"
#include "offline/samples/joint_samples.hpp"
#include "tpf/common/error.hpp"

namespace tpf::cli {

/// read_logs of `paths` (only the columns the fit reads are parsed and kept), printing its notes,
/// the joined log's quality (several files) and the torque-sensor lines that name a flat or
/// missing sensor.
inline offline::Log read_command_logs(const std::vector<std::string>& paths) {
  std::vector<std::string> notes;
  offline::Log log = offline::read_logs(paths, &notes, offline::identification_column);
  for (const std::string& n : notes)
    std::printf("note: %s\n", n.c_str());
  if (log.file_count() > 1) std::printf("%s\n", log.quality.summary(log.columns).c_str());
  for (const std::string& line : offline::torque_sensor_problems(log, log.joint_count()))
    std::printf("%s\n", line.c_str());
  return log;
}

/// One log an estimator-running command (calibrate, evaluate, train) replays, read whole, its
/// quality said on stderr ("log cal.csv: 8000 rows, 20.0 s at 400 Hz; 0 gaps; no missing
/// values"), with --quiet too where the reader left something out or doubted it (missing
/// values, a skipped row, a rate note). Rows with a missing value are the estimator's faulty
/// cycles (it holds its last estimate), counted here; a log without a row is refused.
inline offline::Log read_replayed_log(const std::string& path, bool quiet) {
  offline::Log log = offline::read_log(path);
  if (log.rows() == 0) throw Error::at(path, 0, "", "no rows: nothing to replay");
  if (!quiet || log.quality.missing_total() > 0 || !log.quality.notes.empty()) {
    std::fprintf(stderr, "log %s: %s\n", path.c_str(), log.quality.summary(log.columns).c_str());
    if (log.quality.missing_total() > 0)
      std::fprintf(stderr,
                   "  the estimator takes a row with a missing value as a faulty cycle and holds "
                   "its last estimate\n");
  }
  return log;
}

}  // namespace tpf::cli
