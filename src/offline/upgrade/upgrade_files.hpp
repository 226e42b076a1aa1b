// `tpf upgrade`: parameter, estimator and compensator weight files written when tpf computed in
// the log's effort unit (mA for a log of currents) converted to the files of today, every torque
// in N·m. The conversion is exact: each value is divided by the factor the old parameter file
// states it was identified with (its effort_per_newton_metre, 1000/K_t for mA).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace tpf::offline {

/// What to convert. `params` (a version-1 tpf-params file) is required: it holds the factor.
struct UpgradeFiles {
  std::filesystem::path params;     ///< tpf-params version 1 → 2
  std::filesystem::path estimator;  ///< optional: tpf-estimator version 1 or 2 → 3
  std::filesystem::path weights;    ///< optional: a compensator path (one file or <stem>.joint<j>)
};

/// Converts the files in place (each atomically) and returns one line per file written. Reads
/// and checks every file before writing any, and throws tpf::Error naming the file and field
/// when one is not of the old version (e.g. already converted) or is malformed.
std::vector<std::string> upgrade_files(const UpgradeFiles& files);

}  // namespace tpf::offline
