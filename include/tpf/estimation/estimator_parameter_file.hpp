// The estimator parameter file: everything the run-time Estimator needs besides the nominal model
// and the compensator weights (dead bands, σ's, thresholds, pad gain, …), calibrated once offline
// (`tpf calibrate`) and loaded at start-up. Start-up code only (allocates, throws tpf::Error).
#pragma once

#include <filesystem>
#include <string>

#include "tpf/estimation/estimator_parameters.hpp"

namespace tpf {

/// Loads an estimator parameter file (JSON, "format": "tpf-estimator", "version": 3) for N joints.
/// Every field of EstimatorParameters must be present: a missing, unknown, non-finite or
/// out-of-range field, or a joint count other than N, throws tpf::Error "file: field: reason"
/// (e.g. "arm4.estimator.json: skin.detector.on_level_kpa: missing"). Torques (σ's, dead bands)
/// are in N·m; an older version (in the nominal model's effort unit) is refused, naming `tpf
/// upgrade`.
template <int N>
EstimatorParameters<double, N> load_estimator_parameters(const std::filesystem::path& file);

/// Writes every field of `parameters` to `file` (atomically: temporary + rename), `source` (e.g.
/// the calibration log) under "source" for people. Throws tpf::Error naming the file on I/O
/// failure.
template <int N>
void save_estimator_parameters(const std::filesystem::path& file,
                               const EstimatorParameters<double, N>& parameters,
                               const std::string& source);

}  // namespace tpf
