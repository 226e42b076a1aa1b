// End to end without hardware: the arm loop against the emulated PH54 chain and pad board on
// ptys, with faults injected while it runs. Timing asserts are deliberately loose (the machine is
// shared and may run sanitizers); the figures themselves go to docs/hardware-adapters.md.
#include "arm/arm_loop.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "arm/excitation.hpp"
#include "dynamixel/emulator/first_order_plant.hpp"
#include "dynamixel/emulator/motor_chain_emulator.hpp"
#include "dynamixel/ph54/chain_setup.hpp"
#include "dynamixel/ph54/units.hpp"
#include "dynamixel/serial/pty_pair.hpp"
#include "dynamixel/serial/serial_port.hpp"
#include "dynamixel/serial/thread_priority.hpp"
#include "loop_fixture.hpp"
#include "support/allocation_counter.hpp"
#include "teensy/emulator/pad_board_emulator.hpp"
#include "wait_until.hpp"

namespace tpf::arm {
namespace {

using test::kDevicePriority;
constexpr dxl::BusTiming kLoopTiming{4'000'000, 1.0, 3.0};

pad::PadBoardEmulatorOptions board_options(const std::string& link, int garbage) {
  pad::PadBoardEmulatorOptions o;
  o.link_path = link;
  o.startup_garbage_bytes = garbage;
  o.realtime_priority = kDevicePriority;
  return o;
}

/// Emulated arm on ptys plus the host side opened through the real serial code.
struct ArmRig {
  serial::PtyPair motor_pty;
  dxl::emu::FirstOrderPlant plant{4};
  dxl::emu::MotorChainEmulator motors{motor_pty.master(), plant, dxl::emu::arm_chain()};
  pad::PadBoardEmulator board;
  serial::FdTransport port;
  std::unique_ptr<dxl::Bus> bus;
  std::unique_ptr<pad::PadReader> pads;
  const std::vector<std::uint8_t> ids{1, 2, 3, 4};
  dxl::ph54::ChainInfo chain;

  explicit ArmRig(const std::string& name, int garbage = 0)
      : board(board_options(test::temp_path("arm", name + "_pads"), garbage)) {
    motors.start(kDevicePriority);
    board.start();
    port = serial::open_serial_port(motor_pty.slave_path(), 4'000'000);
    // Start-up with a generous timeout; in the loop 1 + 3 ms, so that a late emulator thread
    // costs one cycle, not the loop.
    bus = std::make_unique<dxl::Bus>(port, dxl::BusTiming{4'000'000, 1.0, 200.0});
    chain = dxl::ph54::set_up_chain(*bus, {});
    bus->set_timing(kLoopTiming);
    pads = std::make_unique<pad::PadReader>(pad::PadReaderOptions{
        test::temp_path("arm", name + "_pads"), 5.0, 50.0, 5.0, kDevicePriority});
    pads->start();
    test::wait_until([&] { return pads->stats().frames > 20; });
  }
  ~ArmRig() {
    pads->stop();
    board.stop();
    motors.stop();
  }
};

/// Runs the loop on its own thread at the device priority (best effort), as tpf_arm_loop does.
std::thread start_loop(ArmLoop& loop) {
  return std::thread([&loop] {
    serial::set_current_thread_fifo(kDevicePriority);
    loop.run();
  });
}

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

TEST(ArmLoop, HealthyRunLogsEveryCycleInTheTpfFormat) {
  ArmRig rig("healthy");
  const test::TempFile log_file("arm", "healthy.csv");
  const std::string& log_path = log_file.path();
  offline::LogMetadata meta;
  meta.set("robot", "arm4");
  meta.set("rate_hz", "400");
  meta.set("note", "simulated: emulated arm (test)");
  LogRecorder log(log_path, RecordedColumns{4, 16, false}, meta);
  dxl::ph54::ChainStateReader reader(*rig.bus, rig.ids, rig.chain.fast_sync_read);
  ArmLoopOptions options;
  options.cycles = 200;  // 0.5 s
  ArmLoop loop(*rig.bus, reader, rig.ids, rig.pads.get(), &log, options);
  start_loop(loop).join();
  log.close();
  const ArmLoopReport r = loop.report();
  EXPECT_EQ(r.timing.cycles, 200u);
  EXPECT_LT(r.motor_read_failures, 100u);  // loose: the emulator shares a loaded machine
  EXPECT_LT(r.timing.lateness_max_s, 0.5);
  EXPECT_EQ(r.bus.crc_errors, 0u);
  EXPECT_EQ(r.log_rows_dropped, 0u);

  const auto lines = read_lines(log_path);
  ASSERT_EQ(lines.size(), 4u + 1u + 200u);
  EXPECT_EQ(lines[0], "# tpf-log: 1");
  EXPECT_EQ(lines[2], "# rate_hz: 400");
  EXPECT_EQ(lines[4].substr(0, 41), "t,q1,q2,q3,q4,dq1,dq2,dq3,dq4,i1,i2,i3,i4");
  EXPECT_NE(lines[4].find(",p16"), std::string::npos);
  double last_t = -1.0;
  int with_pads = 0;
  for (std::size_t k = 5; k < lines.size(); ++k) {
    std::stringstream row(lines[k]);
    std::string field;
    std::vector<std::string> fields;
    while (std::getline(row, field, ','))
      fields.push_back(field);
    ASSERT_EQ(fields.size(), 1u + 12u + 16u) << lines[k];
    const double t = std::stod(fields[0]);
    EXPECT_GT(t, last_t);  // t strictly increases
    last_t = t;
    if (fields[13] != "nan") {
      ++with_pads;
      EXPECT_NEAR(std::stod(fields[13]), 2.0, 1.0001);  // 2 + sin(·) kPa
    }
  }
  EXPECT_GT(with_pads, 100);
  EXPECT_GE(last_t, 199 * 0.0025);
}

TEST(ArmLoop, FaultsAreCountedAndTheLoopKeepsItsPeriod) {
  ArmRig rig("faults", 40);
  dxl::ph54::ChainStateReader reader(*rig.bus, rig.ids, rig.chain.fast_sync_read);
  ArmLoopOptions options;
  options.cycles = 400;  // 1 s
  ArmLoop loop(*rig.bus, reader, rig.ids, rig.pads.get(), nullptr, options);
  std::thread runner = start_loop(loop);
  const auto pause = [](long ms) {
    const timespec t{0, ms * 1'000'000};
    clock_nanosleep(CLOCK_MONOTONIC, 0, &t, nullptr);
  };
  pause(100);
  rig.motors.corrupt_next_responses(3);  // CRC errors
  pause(40);
  rig.motors.split_responses(true);  // partial packets
  pause(60);
  rig.motors.split_responses(false);
  rig.motors.set_silent(3, true);  // a motor that does not answer
  pause(40);
  rig.motors.set_silent(3, false);
  rig.motors.raise_hardware_error(2, dxl::ph54::overload);  // Alert bit
  rig.motors.garbage_before_next_response(9);
  rig.board.unplug();  // pad board unplugged …
  pause(80);
  rig.board.replug();  // … and back
  runner.join();

  const ArmLoopReport r = loop.report();
  EXPECT_EQ(r.timing.cycles, 400u);
  EXPECT_GE(r.bus.crc_errors, 1u);  // ≤ 3: a corrupted answer that arrives late is a timeout
  EXPECT_GE(r.bus.timeouts, 1u);
  EXPECT_GE(r.motor_read_failures, 4u);
  EXPECT_LT(r.motor_read_failures, 300u);  // the loop recovered after each fault
  EXPECT_GE(r.alert_events, 1u);
  EXPECT_EQ(r.hardware_error[1], dxl::ph54::overload);
  EXPECT_EQ(r.hardware_error[0], 0u);
  EXPECT_GE(r.bus.garbage_bytes, 9u);
  EXPECT_GE(r.pads.disconnects, 1u);
  EXPECT_GE(r.pads.connects, 2u);
  EXPECT_GT(r.pad_stale_cycles, 10u);       // no pad data while unplugged
  EXPECT_LT(r.timing.lateness_max_s, 0.5);  // generous: no cycle stalled the loop
}

TEST(ArmLoop, CycleDoesNotAllocate) {
  ArmRig rig("alloc");
  dxl::ph54::ChainStateReader reader(*rig.bus, rig.ids, rig.chain.fast_sync_read);
  ArmLoopOptions options;
  options.cycles = 40;
  EstimatorFiles files;  // the core Estimator runs in every cycle
  files.params = std::string(TPF_TEST_DATA_DIR) + "/arm4.params.json";
  files.robot = std::string(TPF_TEST_DATA_DIR) + "/arm4.robot.json";
  files.pads = std::string(TPF_TEST_DATA_DIR) + "/arm4.pads.json";
  files.estimator = std::string(TPF_TEST_DATA_DIR) + "/arm4.estimator.json";
  files.weights = std::string(TPF_TEST_DATA_DIR) + "/weights/arm4.tcn.json";
  EstimatorHook estimator(files);
  ArmLoop loop(*rig.bus, reader, rig.ids, rig.pads.get(), nullptr, options, &estimator);
  test::AllocationCounter allocations;
  loop.run();
  EXPECT_EQ(allocations.count(), 0u);
  EXPECT_EQ(loop.report().estimator.updates, 40u);
}

}  // namespace
}  // namespace tpf::arm

namespace tpf::arm {
namespace {

TEST(ArmLoop, ExcitationDrivesPositionGoalsThroughSyncWrite) {
  ArmRig rig("excite");
  dxl::ph54::ChainConfig config;
  config.mode = dxl::ph54::OperatingMode::position;
  rig.chain = dxl::ph54::set_up_chain(*rig.bus, config);
  dxl::ph54::hold_present_position(*rig.bus, rig.ids);  // as tpf_arm_loop --excite does
  dxl::ph54::ChainStateReader reader(*rig.bus, rig.ids, rig.chain.fast_sync_read);
  ArmLoopOptions options;
  options.cycles = 400;  // 1 s: the ramp reaches half amplitude
  options.excitation_rad = 0.3;
  ArmLoop loop(*rig.bus, reader, rig.ids, rig.pads.get(), nullptr, options);
  start_loop(loop).join();
  // Goal Position of joint 4 lies on the multisine near the end of the run (the last cycles'
  // reads may have failed, so the last goal written can be a few cycles old). The emulator may
  // still be working through the last Sync Writes: wait (bounded) for them.
  const double t_end = loop.last_sample().t;
  std::int32_t goal = 0;
  const auto on_trajectory = [&] {
    goal = static_cast<std::int32_t>(rig.motors.register_value(4, dxl::ph54::goal_position, 4));
    for (double t = t_end - 0.1; t <= t_end + 1e-9; t += 0.0005)
      if (std::abs(goal * dxl::ph54::kRadPerPulse - excitation_goal(3, t, 0.3, 0.0)) < 1e-3)
        return true;
    return false;
  };
  EXPECT_TRUE(test::wait_until(on_trajectory)) << goal * dxl::ph54::kRadPerPulse;
  EXPECT_GT(std::abs(goal), 1000);
  EXPECT_EQ(loop.report().bus.tx_failures, 0u);
}

}  // namespace
}  // namespace tpf::arm
