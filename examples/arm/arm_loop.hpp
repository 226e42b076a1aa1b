// The arm's 400 Hz loop: absolute deadlines on CLOCK_MONOTONIC (clock_nanosleep TIMER_ABSTIME),
// one Fast Sync Read of the chain per cycle, the latest pad sample, the core Estimator
// (EstimatorHook), an optional excitation (Sync Write Goal Position) and a log row. Faults are
// counted, never fatal.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>

#include "arm/estimator_hook.hpp"
#include "arm/log_recorder.hpp"
#include "arm/loop_statistics.hpp"
#include "dynamixel/ph54/chain_state_reader.hpp"
#include "teensy/host/pad_reader.hpp"

namespace tpf::arm {

struct ArmLoopOptions {
  double rate_hz = 400.0;
  std::uint64_t cycles = 0;     ///< 0: until request_stop()
  double pad_stale_s = 0.020;   ///< older pad frames are logged as missing
  double excitation_rad = 0.0;  ///< > 0: position-mode multisine (excitation.hpp)
};

struct ArmLoopReport {
  TimingSummary timing;
  std::uint64_t missed_deadlines = 0;     ///< whole periods skipped because a cycle overran
  std::uint64_t motor_read_failures = 0;  ///< cycles without motor data
  dxl::BusCounters bus;
  std::uint64_t alert_events = 0;  ///< onsets of the Alert bit, per motor
  std::array<std::uint8_t, dxl::ph54::kMaxChainMotors> hardware_error{};  ///< last 518 read
  std::uint64_t pad_stale_cycles = 0;
  bool pads_used = false;
  pad::PadReaderStats pads;
  std::uint64_t log_rows_dropped = 0;
  bool estimator_used = false;
  EstimatorStatistics estimator;
};

class ArmLoop {
 public:
  /// `ids` as given to `motors`. `pads`, `log` and `estimator` may be null. All must outlive the
  /// loop.
  ArmLoop(dxl::Bus& bus, dxl::ph54::ChainStateReader& motors, std::span<const std::uint8_t> ids,
          pad::PadReader* pads, LogRecorder* log, ArmLoopOptions options,
          EstimatorHook* estimator = nullptr);

  /// Runs on the calling thread until `cycles` are done or request_stop().
  void run();
  void request_stop() noexcept { stop_.store(true); }
  /// Call after run() (allocates for the percentiles).
  ArmLoopReport report() const;
  /// The sample of the last cycle run.
  const CycleSample& last_sample() const noexcept { return sample_; }
  /// CLOCK_MONOTONIC [ns] at which run() started: a sample's t is counted from here.
  serial::MonoNs start_ns() const noexcept { return start_ns_; }

 private:
  void cycle(std::int64_t start_ns);
  void check_alerts();
  void read_pads(std::int64_t now_ns);
  void excite();

  dxl::Bus& bus_;
  dxl::ph54::ChainStateReader& motors_;
  std::array<std::uint8_t, dxl::ph54::kMaxChainMotors> ids_{};
  pad::PadReader* pads_;
  LogRecorder* log_;
  ArmLoopOptions options_;
  EstimatorHook* estimator_;
  serial::MonoNs start_ns_ = 0;
  std::atomic<bool> stop_{false};
  LoopStatistics statistics_;
  CycleSample sample_;
  std::array<dxl::ph54::JointReading, dxl::ph54::kMaxChainMotors> joints_{};
  std::array<bool, dxl::ph54::kMaxChainMotors> alerted_{};
  std::array<double, dxl::ph54::kMaxChainMotors> q_start_{};
  bool have_start_ = false;
  std::int64_t bus_time_ns_ = 0;
  std::int64_t estimator_time_ns_ = 0;
  ArmLoopReport report_;
};

}  // namespace tpf::arm
