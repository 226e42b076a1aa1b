// End to end on the digital twin: tpf_arm_loop's parts (serial, Fast Sync Read, pad reader,
// 400 Hz loop, core Estimator) against the PH54 chain and pad board emulated on ptys, both driven
// by one twin (simulated data) in which a hand pushes on a pad while the drives hold the arm.
// Faults are injected while the loop runs. The run is bounded by deadlines, never by a timed
// assertion: the loop runs a fixed number of cycles, every bus and pad read has a deadline, and
// the test gives up (and fails) if the loop does not finish within a generous bound.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include "arm/arm_loop.hpp"
#include "arm/estimator_hook.hpp"
#include "arm/log_recorder.hpp"
#include "arm/report_printer.hpp"
#include "dynamixel/emulator/motor_chain_emulator.hpp"
#include "dynamixel/ph54/chain_setup.hpp"
#include "dynamixel/serial/pty_pair.hpp"
#include "dynamixel/serial/serial_port.hpp"
#include "dynamixel/serial/thread_priority.hpp"
#include "loop_fixture.hpp"
#include "offline/log/read_log.hpp"
#include "offline/sim/scenario.hpp"
#include "support/arm_fixture.hpp"
#include "teensy/emulator/pad_board_emulator.hpp"
#include "tpf/estimation/estimator_status.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "twin/twin_motor_plant.hpp"
#include "wait_until.hpp"

namespace tpf::arm {
namespace {

using test::data_path;
using test::kDevicePriority;

constexpr std::uint64_t kCycles = 1600;  // 4 s at 400 Hz
// The push (twin time): ramps over 0.25 s, held 1.5 s, on pad kPad with kNormal newtons on a
// 6 cm² contact (the pads' reference area: the twin's pad gain is then exactly 1.5 kPa/N).
constexpr int kPad = 4;  // forearm_top, on link 4: loads joints 2–4 at the held pose
constexpr double kOn = 1.6, kFull = 1.85, kRelease = 3.35, kOff = 3.6, kNormal = 12.0;

offline::ContactScript one_push() {
  offline::ContactScript script;
  offline::ContactEvent e;
  e.pad = kPad;
  e.t_on = kOn;
  e.t_full = kFull;
  e.t_release = kRelease;
  e.t_off = kOff;
  e.normal_n = kNormal;
  e.area_cm2 = 6.0;
  script.add(e);
  return script;
}

void pause_ms(long ms) {
  const timespec t{ms / 1000, (ms % 1000) * 1'000'000};
  clock_nanosleep(CLOCK_MONOTONIC, 0, &t, nullptr);
}

TEST(TwinArmLoop, EstimatorFollowsTheTwinsPushThroughInjectedFaults) {
  // The twin: static-contacts scenario (robot, friction, PH54 drives, sensor noise) with one push.
  const offline::Scenario scenario =
      offline::load_scenario(data_path("scenarios/static-contacts.json"));
  dxl::emu::TwinMotorPlant plant(scenario, {7, 2000 * 6});
  plant.set_contacts(one_push());

  // Devices on ptys; garbage precedes the pad board's first frame (and, below, a motor status).
  serial::PtyPair motor_pty;
  dxl::emu::MotorChainEmulator motors(motor_pty.master(), plant, dxl::emu::arm_chain());
  pad::PadBoardEmulatorOptions board_options;
  board_options.link_path = test::temp_path("twin", "pads");
  board_options.startup_garbage_bytes = 40;
  board_options.realtime_priority = kDevicePriority;
  board_options.source = [&plant](std::span<float> kpa) { return plant.pad_pressures(kpa); };
  pad::PadBoardEmulator board(board_options);
  motors.start(kDevicePriority);
  board.start();

  // Files first, as tpf_arm_loop does: once the motors hold, the bus watchdog (100 ms) wants
  // the loop running.
  EstimatorFiles files;
  files.params = data_path("arm4.params.json");
  files.robot = data_path("arm4.robot.json");
  files.pads = data_path("arm4.pads.json");
  files.estimator = data_path("arm4.estimator.json");  // calibrated on a SIMULATED twin log
  files.weights = data_path("weights/arm4.tcn.json");
  files.trace_capacity = kCycles;
  EstimatorHook estimator(files);
  pad::PadReader pads(
      pad::PadReaderOptions{test::temp_path("twin", "pads"), 5.0, 50.0, 5.0, kDevicePriority});
  pads.start();
  // Host side as tpf_arm_loop sets it up: generous start-up timeouts, hold the pose, then 1 + 3 ms.
  serial::FdTransport port = serial::open_serial_port(motor_pty.slave_path(), 4'000'000);
  const std::vector<std::uint8_t> ids{1, 2, 3, 4};
  dxl::Bus bus(port, dxl::BusTiming{4'000'000, 1.0, 200.0});
  motors.garbage_before_next_response(17);  // garbage at start, before the first ping's status
  dxl::ph54::ChainConfig config;
  config.mode = dxl::ph54::OperatingMode::position;
  const dxl::ph54::ChainInfo chain = dxl::ph54::set_up_chain(bus, config);
  dxl::ph54::hold_present_position(bus, ids);
  bus.set_timing(dxl::BusTiming{4'000'000, 1.0, 3.0});

  dxl::ph54::ChainStateReader reader(bus, ids, chain.fast_sync_read);
  ArmLoopOptions options;
  options.cycles = kCycles;
  // Recorded as tpf_arm_loop records: the motors, the pads and the estimator's answer.
  const test::TempFile log_file("twin", "twin-loop.csv");
  const std::string& log_path = log_file.path();
  offline::LogMetadata meta;
  meta.set("robot", "arm4");
  meta.set("rate_hz", "400");
  LogRecorder log(log_path, RecordedColumns{4, EstimatorHook::kPads, true}, meta);
  ArmLoop loop(bus, reader, ids, &pads, &log, options, &estimator);
  std::atomic<bool> done{false}, realtime{false};
  const double steal_before = test::stolen_cpu_seconds();
  std::thread runner([&] {
    realtime.store(serial::set_current_thread_fifo(kDevicePriority));
    loop.run();
    done.store(true);
  });

  // Faults while it runs (loop time; the push starts later, at twin time 1.6 s).
  pause_ms(150);
  motors.corrupt_next_responses(3);  // CRC errors
  board.corrupt_next_frames(2);
  pause_ms(50);
  motors.split_responses(true);  // partial packets
  pause_ms(60);
  motors.split_responses(false);
  motors.set_silent(3, true);  // a motor that does not answer
  pause_ms(40);
  motors.set_silent(3, false);
  motors.garbage_before_next_response(9);
  board.unplug();  // the pad board unplugged …
  pause_ms(80);
  board.replug();  // … and back
  // The alert (motor 2 shuts down, as a PH54 does on a hardware error) after the push.
  test::wait_until([&] { return done.load() || loop.last_sample().t > 3.75; }, 30.0);
  motors.raise_hardware_error(2, dxl::ph54::overload);

  const bool finished = test::wait_until([&] { return done.load(); }, 30.0);
  if (!finished) loop.request_stop();
  runner.join();
  log.close();
  pads.stop();
  board.stop();
  motors.stop();
  const double stolen_s = test::stolen_cpu_seconds() - steal_before;
  // Without SCHED_FIFO (no CAP_SYS_NICE) the loop keeps its period only on an otherwise idle CPU.
  SCOPED_TRACE(realtime.load() ? "the loop ran SCHED_FIFO"
                               : "SCHED_FIFO refused: the loop ran at normal priority");
  ASSERT_TRUE(finished) << "the loop did not finish " << kCycles << " cycles within 30 s";

  // Every fault is counted.
  const ArmLoopReport r = loop.report();
  print_report(stdout, r, ids.size());  // timing and counters: what a failure below needs
  std::printf("CPU stolen by the hypervisor during the run: %.2f s\n", stolen_s);
  EXPECT_EQ(r.timing.cycles, kCycles);
  EXPECT_GE(r.bus.crc_errors, 1u);
  EXPECT_GE(r.bus.garbage_bytes, 9u + 17u);
  EXPECT_GE(r.bus.timeouts, 1u);  // the silent motor
  EXPECT_GE(r.motor_read_failures, 4u);
  EXPECT_GE(r.alert_events, 1u);
  EXPECT_EQ(r.hardware_error[1], dxl::ph54::overload);
  EXPECT_GE(r.pads.crc_errors + r.pads.cobs_errors, 1u);
  EXPECT_GE(r.pads.startup_bytes, 1u);
  EXPECT_GE(r.pads.disconnects, 1u);
  EXPECT_GE(r.pads.connects, 2u);
  EXPECT_GT(r.pad_stale_cycles, 10u);
  // The loop keeps its period: a fixed number of cycles on the absolute-deadline grid, so the
  // last one starts 4 s after the first unless whole periods were skipped (counted).
  EXPECT_NEAR(loop.last_sample().t, (kCycles - 1 + r.missed_deadlines) / 400.0, 0.05);
  // Fewer than 10 % missed, besides the periods the hypervisor took: whatever its priority, the
  // loop (or the emulator it waits for) loses the periods its CPU is stolen. 0 on bare metal.
  const auto stolen_periods = static_cast<std::uint64_t>(stolen_s * 400.0);
  EXPECT_LT(r.missed_deadlines, kCycles / 10 + stolen_periods)
      << stolen_s << " s of CPU stolen by the hypervisor during the run";
  EXPECT_LT(r.motor_read_failures, kCycles / 4);

  // The estimator ran on every cycle; each faulty cycle is flagged, not estimated.
  const EstimatorStatistics& e = r.estimator;
  EXPECT_EQ(e.updates, kCycles);
  EXPECT_EQ(e.status_bit[0], r.motor_read_failures);  // a failed read is skipped (NaN input)
  EXPECT_LE(e.status_bit[4], r.pad_stale_cycles);     // stale pads: pad data invalid …
  EXPECT_GE(e.status_bit[4] + r.motor_read_failures, r.pad_stale_cycles);  // … unless skipped
  EXPECT_GT(e.clean, kCycles / 2);
  EXPECT_EQ(e.non_finite_estimates, 0u);
  ASSERT_EQ(estimator.trace().size(), kCycles);

  // The log holds every cycle, and its estimates are the estimator's: a recorded run replays
  // and scores with the tools.
  EXPECT_EQ(r.log_rows_dropped, 0u);
  const offline::Log recorded = offline::read_log(log_path);
  ASSERT_EQ(recorded.rows(), static_cast<Eigen::Index>(kCycles));
  for (std::size_t k = 0; k < kCycles; ++k) {
    const EstimateRecord& rec = estimator.trace()[k];
    const auto row = static_cast<Eigen::Index>(k);
    ASSERT_EQ(recorded.col("t")[row], rec.t);
    ASSERT_EQ(recorded.col("est_status")[row], static_cast<double>(rec.status));
    if (rec.status & (kStatusNonFiniteInput | kStatusStaleTime))  // skipped: no numbers
      ASSERT_TRUE(std::isnan(recorded.col("est_pad")[row])) << "cycle " << k;
    else
      ASSERT_EQ(recorded.col("est_pad")[row], rec.contact_pad + 1.0) << "cycle " << k;
    for (int j = 0; j < 4; ++j) {
      const double logged = recorded.col("est_tau_ext" + std::to_string(j + 1))[row];
      if (std::isnan(rec.external_torque_nm[j]))
        ASSERT_TRUE(std::isnan(logged)) << "cycle " << k << " joint " << j + 1;
      else
        ASSERT_EQ(logged, rec.external_torque_nm[j]) << "cycle " << k << " joint " << j + 1;
    }
  }

  // Estimates against the twin's truth. Loop time t maps to twin time t + offset (both count
  // CLOCK_MONOTONIC; the twin is advanced in real time from the emulator's start).
  const double offset = static_cast<double>(loop.start_ns() - motors.boot_ns()) * 1e-9;
  const auto& truth = plant.truth();
  ASSERT_GT(truth.size(), 2000u * 4);
  const auto truth_at = [&](double t) -> const dxl::emu::TwinTruth& {
    const auto k = static_cast<std::size_t>(std::clamp(t * 2000.0, 0.0, truth.size() - 1.0));
    return truth[k];
  };
  JointVector<double, 4> estimated = JointVector<double, 4>::Zero(), expected = estimated;
  int held = 0, held_on_pad = 0, free = 0, free_flagged = 0, skipped = 0;
  int skipped_without_numbers = 0;
  double force = 0.0;
  for (const EstimateRecord& rec : estimator.trace()) {
    const double t = rec.t + offset;
    if (rec.status & (kStatusNonFiniteInput | kStatusStaleTime)) {
      ++skipped;  // flagged, and no numbers
      skipped_without_numbers += std::isnan(rec.external_torque_nm[1]) && rec.contact_pad < 0;
      continue;
    }
    if (t > kFull + 0.3 && t < kRelease - 0.05) {  // the push held
      ++held;
      held_on_pad += rec.contact_pad == kPad;
      estimated += rec.external_torque_nm;
      expected += truth_at(t).tau_ext;
      force += rec.normal_force_n;
    } else if (t > 1.1 && t < kOn - 0.05) {  // after the faults, before the push
      ++free;
      free_flagged += rec.contact_pad >= 0;
    }
  }
  EXPECT_EQ(skipped, static_cast<int>(r.motor_read_failures));
  EXPECT_EQ(skipped_without_numbers, skipped);
  ASSERT_GT(held, 300);
  ASSERT_GT(free, 50);
  estimated /= held;
  expected /= held;
  force /= held;
  // The skin flags the pushed pad on every held cycle and nothing before the push.
  EXPECT_EQ(held_on_pad, held);
  EXPECT_EQ(free_flagged, 0);
  // External torque while the drives hold the arm: the static estimate is the change of the
  // residual since the push began, and the change of the joint's friction is part of it. A held
  // joint's friction can swing anywhere within ±τ_s (its breakaway torque), so the estimate is
  // right to 2·τ_s,j (+ 0.25 N·m for noise and the compensator); joints the push loads by more
  // than that must get its sign. (Measured, simulated: joint 2 5.2–5.8 vs 2.89 N·m, joint 3
  // 2.5 vs 1.32 N·m; joints 1 and 4 exactly 0 behind their dead bands, truth ≈ 0.)
  const NominalModel<double, 4> nominal =
      load_nominal_model<4>(data_path("arm4.params.json"), data_path("arm4.robot.json"));
  for (int j = 0; j < 4; ++j) {
    const double swing = 2.0 * nominal.friction.static_friction[j];
    EXPECT_NEAR(estimated[j], expected[j], swing + 0.25) << "joint " << j + 1;
    if (std::abs(expected[j]) > 0.5) {
      EXPECT_GT(estimated[j] * expected[j], 0.0) << "joint " << j + 1;
    }
  }
  // The contact force: a push (positive normal force), within the pad prior's ±50 % spread
  // (ContactForceSettings::prior_relative) widened by the friction error of the torque above.
  EXPECT_GT(force, 0.5 * kNormal);
  EXPECT_LT(force, 2.5 * kNormal);
}

}  // namespace
}  // namespace tpf::arm
