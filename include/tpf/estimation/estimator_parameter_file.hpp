// The estimator parameter file: everything the run-time Estimator needs besides the nominal model
// and the compensator weights (dead bands, σ's, thresholds, pad gain, …), calibrated once offline
// (`tpf calibrate`) and loaded at start-up. Start-up code only (allocates, throws tpf::Error).
#pragma once

#include <filesystem>
#include <string>

#include "tpf/estimation/estimator_parameters.hpp"

namespace tpf {

/// Loads an estimator parameter file (JSON, "format": "tpf-estimator", "version": 3) for the
/// file's joint count ("joints"; `joints` > 0: it must be that many). Every field of
/// EstimatorParameters must be present: a missing, unknown, non-finite or out-of-range field, or
/// a joint count other than `joints`, throws tpf::Error "file: field: reason" (e.g.
/// "arm4.estimator.json: skin.detector.on_level_kpa: missing"; "…: joints: the file is for 4
/// joints, the arm here has 7 …"). Torques (σ's, dead bands) are in N·m; an older version (in
/// the nominal model's effort unit) is refused, naming `tpf upgrade`.
EstimatorParameters<double, Eigen::Dynamic> load_estimator_parameters(
    const std::filesystem::path& file, int joints = 0);

/// Writes every field of `parameters` to `file` (atomically: temporary + rename), `source` (e.g.
/// the calibration log) under "source" for people. Throws tpf::Error naming the file on I/O
/// failure, or when the per-joint vectors do not all have one joint count.
void save_estimator_parameters(const std::filesystem::path& file,
                               const EstimatorParameters<double, Eigen::Dynamic>& parameters,
                               const std::string& source);

/// load_estimator_parameters for a program of N joints: the file must be of an N-joint arm
/// (header-only conversion, joint_count_cast).
template <int N>
EstimatorParameters<double, N> load_estimator_parameters(const std::filesystem::path& file) {
  return joint_count_cast<N>(load_estimator_parameters(file, N == Eigen::Dynamic ? 0 : N));
}

/// save_estimator_parameters of an N-joint program's parameters.
template <int N>
void save_estimator_parameters(const std::filesystem::path& file,
                               const EstimatorParameters<double, N>& parameters,
                               const std::string& source) {
  save_estimator_parameters(file, joint_count_cast<Eigen::Dynamic>(parameters), source);
}

}  // namespace tpf
