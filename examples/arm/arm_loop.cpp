#include "arm/arm_loop.hpp"

#include <algorithm>
#include <cerrno>

#include "arm/excitation.hpp"
#include "dynamixel/ph54/chain_setup.hpp"
#include "dynamixel/ph54/control_table.hpp"
#include "dynamixel/ph54/units.hpp"

namespace tpf::arm {

using serial::MonoNs;
using serial::monotonic_now;

ArmLoop::ArmLoop(dxl::Bus& bus, dxl::ph54::ChainStateReader& motors,
                 std::span<const std::uint8_t> ids, pad::PadReader* pads, LogRecorder* log,
                 ArmLoopOptions options, EstimatorHook* estimator)
    : bus_(bus), motors_(motors), pads_(pads), log_(log), options_(options), estimator_(estimator) {
  std::copy_n(ids.begin(), std::min(ids.size(), ids_.size()), ids_.begin());
  sample_.joints = std::min(motors_.size(), kMaxJoints);  // the log and estimator take ≤ 8
}

void ArmLoop::run() {
  const auto period = static_cast<MonoNs>(1e9 / options_.rate_hz);
  const MonoNs start = monotonic_now();
  start_ns_ = start;
  MonoNs deadline = start + period;
  for (std::uint64_t n = 0; !stop_.load(std::memory_order_relaxed); ++n) {
    if (options_.cycles != 0 && n >= options_.cycles) break;
    const timespec wake = serial::to_timespec(deadline);
    while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &wake, nullptr) == EINTR) {
    }
    const MonoNs woke = monotonic_now();
    sample_.cycle = n;
    cycle(start);
    statistics_.record(static_cast<double>(woke - deadline) * 1e-9,
                       static_cast<double>(bus_time_ns_) * 1e-9,
                       static_cast<double>(estimator_time_ns_) * 1e-9);
    deadline += period;
    for (const MonoNs now = monotonic_now(); now > deadline; deadline += period)
      ++report_.missed_deadlines;  // overran: keep the grid, skip whole periods
  }
}

void ArmLoop::cycle(MonoNs start) {
  const MonoNs t0 = monotonic_now();
  const dxl::CommResult r = motors_.read(std::span(joints_).first(motors_.size()));
  sample_.t = static_cast<double>(t0 - start) * 1e-9;
  sample_.motors_valid = r == dxl::CommResult::success;
  if (sample_.motors_valid) {
    for (std::size_t j = 0; j < sample_.joints; ++j) {
      sample_.q[j] = joints_[j].position_rad;
      sample_.dq[j] = joints_[j].velocity_rad_s;
      sample_.i[j] = joints_[j].current_mA;
    }
    check_alerts();
    if (options_.excitation_rad > 0.0) excite();
  } else {
    ++report_.motor_read_failures;
  }
  bus_time_ns_ = monotonic_now() - t0;  // read, alert follow-up and goal write
  read_pads(t0);
  if (estimator_ != nullptr) {
    const MonoNs e0 = monotonic_now();
    estimator_->update(sample_);
    estimator_time_ns_ = monotonic_now() - e0;
    sample_.estimate = estimator_->estimate();
  }
  if (log_ != nullptr) log_->push(sample_);
}

void ArmLoop::check_alerts() {
  for (std::size_t j = 0; j < motors_.size(); ++j) {
    const bool alert = joints_[j].error.alert();
    if (alert && !alerted_[j]) {  // onset: read Hardware Error Status(518) once
      ++report_.alert_events;
      std::uint8_t bits = 0;
      if (dxl::ph54::read_hardware_error(bus_, ids_[j], bits)) report_.hardware_error[j] = bits;
    }
    alerted_[j] = alert;
  }
}

void ArmLoop::read_pads(MonoNs now) {
  sample_.pads_valid = false;
  if (pads_ == nullptr) return;
  pad::PadSample pad;
  if (pads_->latest(pad)) {
    sample_.pad_age_s = static_cast<double>(now - pad.device_time_ns) * 1e-9;
    sample_.pads = std::min<std::size_t>(pad.n, kMaxPads);
    std::copy_n(pad.kpa, sample_.pads, sample_.p.begin());
    sample_.contact_mask = pad.contact_mask;
    sample_.pads_valid = sample_.pad_age_s < options_.pad_stale_s;
  }
  if (!sample_.pads_valid) ++report_.pad_stale_cycles;
}

void ArmLoop::excite() {
  const std::size_t n = motors_.size();
  if (!have_start_) {
    std::copy_n(sample_.q.begin(), n, q_start_.begin());
    have_start_ = true;
  }
  std::array<std::uint8_t, 4 * dxl::ph54::kMaxChainMotors> goal{};
  for (std::size_t j = 0; j < n; ++j) {
    const double q = excitation_goal(j, sample_.t, options_.excitation_rad, q_start_[j]);
    dxl::put_le(std::span(goal).subspan(4 * j, 4),
                static_cast<std::uint32_t>(dxl::ph54::rad_to_position(q)));
  }
  bus_.sync_write(dxl::ph54::goal_position, 4, std::span(ids_).first(n),
                  std::span(goal).first(4 * n));
}

ArmLoopReport ArmLoop::report() const {
  ArmLoopReport r = report_;
  r.timing = statistics_.summarize();
  r.bus = bus_.counters();
  r.pads_used = pads_ != nullptr;
  if (pads_ != nullptr) r.pads = pads_->stats();
  if (log_ != nullptr) r.log_rows_dropped = log_->rows_dropped();
  r.estimator_used = estimator_ != nullptr;
  if (estimator_ != nullptr) r.estimator = estimator_->statistics();
  return r;
}

}  // namespace tpf::arm
