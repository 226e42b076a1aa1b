// Kinesthetic teaching in closed loop: the twin's admittance controller follows the external
// torque of an estimator running inside the simulation, with and without the compensator.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "offline/log/log.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "offline/sim/scenario.hpp"

namespace tpf::offline {

/// How the arm answered the hand in one closed-loop run.
struct TeachingLoop {
  std::string name;
  Log log;  ///< the closed-loop recording (SIMULATED)
  /// Per joint RMSE of τ̂_ext − gt_tau_ext over the contact rows [N·m].
  Eigen::VectorXd torque_rmse;
  /// Motion onsets scored: (contact event, joint) pairs whose ideal peak speed is ≥ 0.05 rad/s.
  int onsets = 0;
  /// Mean over onsets of the peak-speed error in the first 0.5 s after the hand takes the pad,
  /// (max|q̇| − max|v*|)/max|v*| in %, split by sign: overshoot (> 0) and undershoot (< 0, given
  /// as a positive number); v* is the ideal admittance velocity M_a·v̇* + D_a·v* = gt_tau_ext.
  double mean_overshoot_percent = 0.0;
  double mean_undershoot_percent = 0.0;
  int overshoots = 0, undershoots = 0;
};

/// Ideal admittance velocity per row from the true external torque (T × N, N·m), integrated with
/// each row's period while gt_contact ≠ 0 (else the reference decays as the controller's does
/// with zero input): v*_{k+1} = v*_k + Δt·(τ_k − D_a·v*_k)/M_a.
Eigen::MatrixXd ideal_admittance_velocity(const Eigen::VectorXd& t, const Eigen::MatrixXd& tau,
                                          const Eigen::VectorXd& contact,
                                          const TeachingConfig& config);

/// Scores one closed-loop recording (see TeachingLoop); `estimate` is τ̂_ext per row [N·m].
void score_teaching_loop(const TeachingConfig& config, const Eigen::MatrixXd& estimate,
                         TeachingLoop& loop);

/// Runs `scenario` (kind teaching) twice with the estimator of `setup` in the loop: once following
/// the proprioceptive estimate (nominal model, dead band 1.5σ_nominal) and once the fused one
/// (static model-free at rest, nominal + TCN moving). Same seed: the same hand.
/// The twin refuses a teaching scenario on a robot without pads.
std::array<TeachingLoop, 2> closed_loop_teaching(const ReplaySetup& setup, const Scenario& scenario,
                                                 std::uint64_t seed, double duration_s);

}  // namespace tpf::offline
