#include "arm/report_printer.hpp"

#include <algorithm>

namespace tpf::arm {

void print_report(std::FILE* out, const ArmLoopReport& r, std::size_t motors) {
  const TimingSummary& t = r.timing;
  std::fprintf(out, "cycles %llu, missed deadlines %llu, cycles without motor data %llu\n",
               static_cast<unsigned long long>(t.cycles),
               static_cast<unsigned long long>(r.missed_deadlines),
               static_cast<unsigned long long>(r.motor_read_failures));
  std::fprintf(out, "period jitter (wake-up lateness) p50 %.1f us, p99 %.1f us, max %.1f us\n",
               t.lateness_p50_s * 1e6, t.lateness_p99_s * 1e6, t.lateness_max_s * 1e6);
  std::fprintf(out, "bus time per cycle p50 %.1f us, p99 %.1f us, max %.1f us\n", t.bus_p50_s * 1e6,
               t.bus_p99_s * 1e6, t.bus_max_s * 1e6);
  if (r.estimator_used)
    std::fprintf(out, "estimator time per cycle p50 %.1f us, p99 %.1f us, max %.1f us\n",
                 t.estimator_p50_s * 1e6, t.estimator_p99_s * 1e6, t.estimator_max_s * 1e6);
  const dxl::BusCounters& b = r.bus;
  std::fprintf(
      out,
      "bus: transactions %llu, timeouts %llu, CRC errors %llu, disconnects %llu, "
      "bad status %llu, garbage bytes %llu, status errors %llu, alerts %llu\n",
      static_cast<unsigned long long>(b.transactions), static_cast<unsigned long long>(b.timeouts),
      static_cast<unsigned long long>(b.crc_errors), static_cast<unsigned long long>(b.disconnects),
      static_cast<unsigned long long>(b.bad_status),
      static_cast<unsigned long long>(b.garbage_bytes),
      static_cast<unsigned long long>(b.status_errors), static_cast<unsigned long long>(b.alerts));
  for (std::size_t j = 0; j < motors; ++j)
    if (r.hardware_error[j] != 0)
      std::fprintf(out, "motor %zu: hardware error status 0x%02X\n", j + 1, r.hardware_error[j]);
  const pad::PadReaderStats& p = r.pads;
  if (!r.pads_used)
    std::fputs("pads: not used\n", out);
  else
    std::fprintf(
        out,
        "pads: frames %llu, frames lost %llu, CRC errors %llu, COBS errors %llu, "
        "format errors %llu, connects %llu, disconnects %llu, stale cycles %llu, "
        "clock drift %.1f ppm\n",
        static_cast<unsigned long long>(p.frames), static_cast<unsigned long long>(p.lost_frames),
        static_cast<unsigned long long>(p.crc_errors),
        static_cast<unsigned long long>(p.cobs_errors),
        static_cast<unsigned long long>(p.format_errors),
        static_cast<unsigned long long>(p.connects), static_cast<unsigned long long>(p.disconnects),
        static_cast<unsigned long long>(r.pad_stale_cycles), p.drift_ppm);
  std::fprintf(out, "alert onsets %llu, log rows dropped %llu\n",
               static_cast<unsigned long long>(r.alert_events),
               static_cast<unsigned long long>(r.log_rows_dropped));
  if (!r.estimator_used) {
    std::fputs("estimator: not used\n", out);
    return;
  }
  const EstimatorStatistics& e = r.estimator;
  std::fprintf(out,
               "estimator: updates %llu, clean %llu, contact cycles %llu, static cycles %llu, "
               "non-finite estimates %llu\n",
               static_cast<unsigned long long>(e.updates), static_cast<unsigned long long>(e.clean),
               static_cast<unsigned long long>(e.contact_cycles),
               static_cast<unsigned long long>(e.static_cycles),
               static_cast<unsigned long long>(e.non_finite_estimates));
  for (int b = 0; b < EstimatorStatistics::kStatusBits; ++b)
    if (e.status_bit[static_cast<std::size_t>(b)] != 0)
      std::fprintf(out, "estimator status: %s %llu\n", estimator_status_name(b),
                   static_cast<unsigned long long>(e.status_bit[static_cast<std::size_t>(b)]));
  std::fputs("estimator: max |tau_ext| over clean cycles [N*m]", out);
  for (std::size_t j = 0; j < std::min<std::size_t>(motors, EstimatorHook::kJoints); ++j)
    std::fprintf(out, " %.2f", e.max_abs_torque_nm[j]);
  std::fputs("\n", out);
}

}  // namespace tpf::arm
