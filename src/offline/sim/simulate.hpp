// The digital twin's entry point: runs a scenario and emits log rows in the project format
// (shared/docs/log-format.md) with gt_* ground truth. Same scenario + seed → same rows, bit for
// bit.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/log/log_metadata.hpp"
#include "offline/sim/scenario.hpp"

namespace tpf::offline {

/// Receives one log row, values in the order of simulation_columns().
using RowSink = std::function<void(std::span<const double>)>;
/// Receives the simulated fraction in [0, 1], about once per simulated second.
using ProgressSink = std::function<void(double)>;
/// Closes the teaching loop through an external estimator: called with each host row (as the
/// RowSink gets it) and returns the estimated external torque τ̂_ext [N·m] that the admittance
/// controller then follows in place of its built-in nominal estimate.
using ExternalTorqueSource = std::function<TwinVector(std::span<const double>)>;

struct SimulationSummary {
  std::size_t rows = 0;          ///< rows emitted
  std::size_t dropped_rows = 0;  ///< cycles lost on purpose (sensor model)
  double simulated_s = 0.0;
};

/// Columns of a simulated log of `joints` joints (j = 1..joints) and `pad_count` pads (k, none
/// without skin): t, q<j>, dq<j>, i<j>, p<k>, temp<j>, then ground truth gt_fric<j> (mA),
/// gt_tau_ext<j> (N·m), gt_ddq<j> (rad/s²), gt_contact, gt_fx, gt_fy, gt_fz (N). A robot with
/// `coupled` motors (coupled_to) logs the joint torques tau<j> = Cᵀ·K_t·i (N·m) in place of
/// i<j>, and its gt_fric<j> is in N·m (simulate.cpp).
std::vector<std::string> simulation_columns(int joints, int pad_count, bool coupled = false);
/// The columns simulate() emits for `scenario` (its robot's joints and pads).
std::vector<std::string> simulation_columns(const Scenario& scenario);

/// Metadata: tpf-log 1, robot (the robot file's name), rate_hz, source "simulated (tpf digital
/// twin)", seed, scenario (name and file), duration, torque constants.
LogMetadata simulation_metadata(const Scenario& scenario, std::uint64_t seed, double duration_s);

/// Runs `scenario` for `duration_s` (the scenario's duration when ≤ 0) with `seed`.
/// Sign convention of the ground truth: gt_tau_ext = Jᵀ·F with F the force the environment (the
/// hand) applies to the robot, so at rest K_t·i ≈ G(q) + friction − gt_tau_ext (coupled motors:
/// tau ≈ G(q) + gt_fric − gt_tau_ext, all N·m).
/// With `external_torque` set, a teaching scenario's admittance controller follows its estimate
/// (one value per joint). Throws tpf::Error when a per-joint vector of `scenario` does not have
/// one entry per joint of its robot, or a teaching scenario's robot has no pads.
SimulationSummary simulate(const Scenario& scenario, std::uint64_t seed, double duration_s,
                           const RowSink& sink, const ProgressSink& progress = {},
                           const ExternalTorqueSource& external_torque = {});

/// simulate() into a log file written with LogWriter (atomic: nothing is left on failure).
SimulationSummary simulate_to_file(const Scenario& scenario, std::uint64_t seed, double duration_s,
                                   const std::filesystem::path& path,
                                   const ProgressSink& progress = {});

/// simulate() into memory (tests, small runs).
Log simulate_to_log(const Scenario& scenario, std::uint64_t seed, double duration_s,
                    const ExternalTorqueSource& external_torque = {});

}  // namespace tpf::offline
