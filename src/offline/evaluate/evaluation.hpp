// `tpf evaluate`: the three estimators (tactile-only, proprioceptive-only, fusion) side by side on
// held-out logs against ground truth.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "offline/evaluate/closed_loop_teaching.hpp"
#include "offline/evaluate/contact_detection.hpp"
#include "offline/evaluate/force_error.hpp"
#include "offline/evaluate/residual_table.hpp"
#include "offline/evaluate/rest_memory.hpp"
#include "offline/log/log.hpp"
#include "offline/replay/replay_estimator.hpp"
#include "tpf/estimation/transition_sigma.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::offline {

/// The estimators compared.
enum class Modality { Tactile, Proprioceptive, Fusion };
inline constexpr int kModalityCount = 3;
/// "tactile-only", "proprioceptive-only", "fusion".
const char* modality_name(Modality m);

/// The logs: a contact-free calibration log for the dead bands (never a test log), held-out
/// contact-free excitation logs (Table I), and optionally a static-contacts log (detection,
/// force error) and a teaching log (external torque while a hand guides the arm).
struct EvaluationLogs {
  const Log* calibration = nullptr;
  std::vector<const Log*> excitation;
  const Log* contacts = nullptr;
  const Log* teaching = nullptr;
  /// Closed-loop teaching: the scenario is simulated again with the estimator in the loop.
  const Scenario* teaching_scenario = nullptr;
  std::uint64_t teaching_seed = 0;
  double teaching_duration_s = 0.0;
};

/// What the calibration log set, per joint (N entries each).
/// σ's and bands in the excitation logs' effort unit (Evaluation::units: mA for logs of currents).
struct Calibration {
  Eigen::VectorXd sigma_nominal, sigma_fused;      ///< transition σ
  Eigen::VectorXd proprioceptive_band;             ///< 1.5·σ_nominal
  Eigen::VectorXd fusion_moving_band;              ///< 1.5·σ_fused
  Eigen::VectorXd fusion_static_band;              ///< the model-free static band
  Eigen::VectorXd compensator_speed_limit;         ///< the compensator's domain [rad/s]
  Eigen::VectorXd compensator_acceleration_limit;  ///< [rad/s²]
  int torque_alarm_samples = 0;                    ///< persistence of the torque-only contact alarm
  double tactile_n = 0.0;  ///< pad on level as a force on the reference pad [N]
};

/// External-torque error while a hand guides the arm (teaching log, rows with gt_contact),
/// per joint RMSE of τ̂_ext − gt_tau_ext [N·m], over all contact rows and over the first 0.3 s
/// after a joint starts moving (motion onset).
struct TeachingErrors {
  std::size_t contact_rows = 0, onset_rows = 0;
  std::array<Eigen::VectorXd, kModalityCount> rmse{};
  std::array<Eigen::VectorXd, kModalityCount> onset_rmse{};
};

struct Evaluation {
  int joints = 0;
  bool has_skin = false;  ///< the estimator has pads (else the tactile rows say "no skin")
  /// The excitation logs' effort unit: Table I, the calibration's σ's and bands and the report's
  /// residual plots are in it (the estimator computes in N·m; the traces below are N·m).
  DriveUnits units;
  /// What every estimator ran with, calibrated on the calibration log.
  Calibration calibration;
  std::vector<ResidualRow> table;  ///< Table I on the held-out excitation logs
  /// The static residual per joint as noise floor and friction memory (the same logs).
  std::vector<RestMemoryRow> rest_memory;
  Eigen::Index excitation_rows = 0;
  bool has_contacts = false, has_teaching = false;
  std::array<DetectionStats, kModalityCount> detection{};
  std::array<ForceErrorStats, kModalityCount> force{};
  TeachingErrors teaching;
  bool has_closed_loop = false;
  std::array<TeachingLoop, 2> closed_loop;  ///< without / with the compensator
  /// Traces kept for the plots (first excitation log, contacts, teaching).
  EstimatorTrace excitation_trace, contacts_trace, teaching_trace;
  /// Teaching log: τ̂_ext of each modality and gt_tau_ext [N·m], T × N.
  std::array<Eigen::MatrixXd, kModalityCount> teaching_torque;
  Eigen::MatrixXd teaching_truth;
};

/// Runs the estimator of `setup` over every log and computes all metrics; its parameters are
/// calibrated here on logs.calibration and left in setup.parameters (save_estimator_parameters
/// writes them for the run-time loop). `progress` receives one line per stage. Throws tpf::Error
/// on bad logs.
Evaluation evaluate(ReplaySetup& setup, const EvaluationLogs& logs,
                    const std::function<void(const std::string&)>& progress = {});

/// The evaluation as JSON text (every number of the report).
std::string evaluation_json(const Evaluation& evaluation);

}  // namespace tpf::offline
