// The core Estimator in the arm loop: built at start-up from files (nominal model, pad layout,
// estimator parameters calibrated offline by `tpf calibrate`, friction-compensator weights),
// updated once per cycle on the real-time thread with the cycle's sample, its outcome counted for
// the report. The assembly is the core's (tpf::load_estimator, arm4.hpp names the types), the same
// the offline tools score: the loop links tpf::core only.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "arm/arm4.hpp"
#include "arm/cycle_sample.hpp"
#include "tpf/estimation/estimator_status.hpp"
#include "tpf/model/model.hpp"

namespace tpf::arm {

/// Where the estimator comes from (tpf::EstimatorFiles: params, robot, pads, estimator, weights;
/// no weights: UncompensatedArmEstimator). Paths default to the project's data/ folder
/// (tpf_arm_loop). The loop measures motor currents; the robot file's torque constants turn
/// them into the N·m the estimator computes in.
struct EstimatorFiles : tpf::EstimatorFiles {
  /// Estimates kept for inspection (one per cycle, reserved at start-up; 0: none).
  std::size_t trace_capacity = 0;
};

/// One cycle's estimate, as kept in the trace. A skipped cycle (non-finite input, stale time)
/// has no estimate: NaN torques and force, contact_pad −1, the reason in `status`.
struct EstimateRecord {
  double t = 0.0;  ///< the cycle's time [s]
  std::uint32_t status = 0;
  int contact_pad = -1;  ///< most loaded pad in contact (0-based), −1: none
  JointVector<double, kArmJoints> external_torque_nm =
      JointVector<double, kArmJoints>::Zero();  ///< τ_ext
  double normal_force_n = 0.0;                  ///< estimated contact normal force at contact_pad
};

/// What the estimator did over a run.
struct EstimatorStatistics {
  static constexpr int kStatusBits = kEstimatorStatusBits;
  std::uint64_t updates = 0;
  std::uint64_t clean = 0;  ///< status 0: estimated from fresh, finite data
  std::array<std::uint64_t, kStatusBits> status_bit{};  ///< cycles with bit b set
  std::uint64_t contact_cycles = 0;                     ///< a pad in contact (skin)
  std::uint64_t static_cycles = 0;                      ///< state machine not in Dynamic
  std::uint64_t non_finite_estimates = 0;  ///< clean cycles whose τ_ext was not finite (bug)
  std::array<double, kArmJoints> max_abs_torque_nm{};  ///< max |τ_ext| over clean cycles
};

class EstimatorHook {
 public:
  static constexpr int kJoints = kArmJoints;
  static constexpr int kPads = kArmPads;
  using Output = EstimatorOutput<double, kJoints>;

  /// Start-up: loads every file and builds the estimator. Throws tpf::Error naming the file and
  /// field on bad input.
  explicit EstimatorHook(const EstimatorFiles& files);

  /// Per cycle (no allocation, no exception, no I/O): the sample's q, q̇, current (mA, through
  /// torque_from_current into N·m) and pad pressures (kPa, channel k → pad k) become an
  /// EstimatorSample. A failed motor read feeds NaN
  /// q (the estimator skips the cycle: kStatusNonFiniteInput); stale or missing pads feed NaN
  /// pressures (kept state: kStatusPadDataInvalid).
  void update(const CycleSample& sample) noexcept;

  /// The last cycle's output (valid after the first update).
  const Output& output() const noexcept { return *output_; }
  /// The last cycle's answer as the log records it (not present before the first update and for
  /// a skipped cycle).
  const CycleEstimate& estimate() const noexcept { return estimate_; }
  const EstimatorStatistics& statistics() const noexcept { return statistics_; }
  std::span<const EstimateRecord> trace() const noexcept { return trace_; }
  /// The estimator's parameters (dead bands, σ), as loaded.
  const EstimatorParameters<double, kArmJoints>& parameters() const noexcept {
    return std::visit(
        [](const auto& e) -> const auto& { return e->parameters(); }, estimator_);
  }
  /// One line on what was loaded (for the start-up print).
  const std::string& description() const noexcept { return description_; }

 private:
  void record_estimate(const Output& out) noexcept;
  void count(const Output& out) noexcept;

  std::variant<std::unique_ptr<ArmEstimator>, std::unique_ptr<UncompensatedArmEstimator>>
      estimator_;
  ArmEstimator::Sample input_;
  Model<double, kArmJoints> model_;  ///< the robot file's: its K_t turns the currents into N·m
  const Output* output_ = nullptr;
  Output empty_;
  CycleEstimate estimate_;
  EstimatorStatistics statistics_;
  std::vector<EstimateRecord> trace_;
  std::string description_;
};

}  // namespace tpf::arm
