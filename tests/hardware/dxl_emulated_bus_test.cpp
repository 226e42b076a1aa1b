// Host Bus and PH54 start-up against the emulated chain, over an in-memory pipe and a real pty
// (termios path), with injected faults. Every wait is bounded by the bus deadlines.
#include <gtest/gtest.h>

#include <array>

#include "dynamixel/bus/bus.hpp"
#include "dynamixel/emulator/first_order_plant.hpp"
#include "dynamixel/emulator/motor_chain_emulator.hpp"
#include "dynamixel/ph54/chain_setup.hpp"
#include "dynamixel/ph54/chain_state_reader.hpp"
#include "dynamixel/ph54/units.hpp"
#include "dynamixel/protocol/fast_sync_read.hpp"
#include "dynamixel/serial/byte_pipe.hpp"
#include "dynamixel/serial/pty_pair.hpp"
#include "dynamixel/serial/serial_port.hpp"
#include "support/allocation_counter.hpp"
#include "tpf/common/error.hpp"
#include "wait_until.hpp"

namespace tpf::dxl {
namespace {

using emu::FirstOrderPlant;
using emu::MotorChainEmulator;

// Generous deadlines: the emulator is a thread on a shared, loaded machine (and under sanitizers).
constexpr BusTiming kTestTiming{4'000'000, 1.0, 200.0};

struct PipeRig {
  serial::BytePipe pipe;
  FirstOrderPlant plant{4};
  MotorChainEmulator emulator;
  Bus bus;
  explicit PipeRig(std::uint8_t firmware = 12)
      : emulator(pipe.b(), plant, emu::arm_chain(firmware)), bus(pipe.a(), kTestTiming) {
    emulator.start();
  }
  ~PipeRig() {
    pipe.close();
    emulator.stop();
  }
};

TEST(DxlEmulatedBus, SetUpWritesRegistersAndChoosesFastSyncRead) {
  PipeRig rig;
  const ph54::ChainInfo info = ph54::set_up_chain(rig.bus, {});
  ASSERT_EQ(info.motors.size(), 4u);
  EXPECT_TRUE(info.fast_sync_read);
  EXPECT_EQ(info.motors[0].model, ph54::kModelPh54_200);
  EXPECT_EQ(info.motors[3].model, ph54::kModelPh54_100);
  for (std::uint8_t id = 1; id <= 4; ++id) {
    EXPECT_EQ(rig.emulator.register_value(id, ph54::return_delay_time, 1), 0u);
    EXPECT_EQ(rig.emulator.register_value(id, ph54::bus_watchdog, 1), 5u);
    EXPECT_EQ(rig.emulator.register_value(id, ph54::operating_mode, 1), 0u);
  }
  EXPECT_EQ(rig.bus.counters().timeouts, 0u);
}

TEST(DxlEmulatedBus, OldFirmwareFallsBackToSyncRead) {
  PipeRig rig(11);
  const ph54::ChainInfo info = ph54::set_up_chain(rig.bus, {});
  EXPECT_FALSE(info.fast_sync_read);
  ph54::ChainStateReader reader(rig.bus, std::array<std::uint8_t, 4>{1, 2, 3, 4},
                                info.fast_sync_read);
  std::array<ph54::JointReading, 4> joints;
  EXPECT_EQ(reader.read(joints), CommResult::success);
}

TEST(DxlEmulatedBus, FastSyncReadReturnsQuantisedPlantState) {
  PipeRig rig;
  const ph54::ChainInfo info = ph54::set_up_chain(rig.bus, {});
  // Current mode, torque on, goal current 0.5 A on joint 2: it accelerates towards 0.5 rad/s.
  ph54::set_torque(rig.bus, {1, 2, 3, 4}, true);
  const std::uint8_t ids[] = {1, 2, 3, 4};
  std::array<std::uint8_t, 8> goal{};
  put_le(std::span(goal).subspan(2, 2), 500);
  ASSERT_EQ(rig.bus.sync_write(ph54::goal_current, 2, ids, goal), CommResult::success);
  ph54::ChainStateReader reader(rig.bus, ids, info.fast_sync_read);
  std::array<ph54::JointReading, 4> joints;
  {
    test::AllocationCounter allocations;
    ASSERT_EQ(reader.read(joints), CommResult::success);
    EXPECT_EQ(allocations.count(), 0u);
  }
  // The plant runs in real time: poll (bounded) until joint 2 has spun up.
  ASSERT_TRUE(test::wait_until([&] {
    return reader.read(joints) == CommResult::success && joints[1].velocity_rad_s > 0.45;
  }));
  EXPECT_NEAR(joints[1].current_mA, 500.0, 1.0);
  EXPECT_LE(joints[1].velocity_rad_s, 0.5 + 1e-3);  // k_v · 0.5 A
  EXPECT_GT(joints[1].position_rad, 0.01);
  EXPECT_EQ(joints[0].current_mA, 0.0);
  // Quantisation: the position is an integer number of pulses.
  const double pulses = joints[1].position_rad / ph54::kRadPerPulse;
  EXPECT_NEAR(pulses, std::round(pulses), 1e-6);
}

// Regression: Goal Current kept its power-on value (Current Limit, 22.74 A) through set-up, so
// Torque Enable = 1 drove joints 1–2 at full current until the test's goal arrived; under load
// FastSyncReadReturnsQuantisedPlantState then read ≈ 16.7 A and 0.69 rad/s on its first poll.
TEST(DxlEmulatedBus, CurrentModeSetUpZeroesGoalCurrentSoTorqueOnStaysStill) {
  PipeRig rig;
  const ph54::ChainInfo info = ph54::set_up_chain(rig.bus, {});
  for (std::uint8_t id = 1; id <= 4; ++id)
    EXPECT_EQ(rig.emulator.register_value(id, ph54::goal_current, 2), 0u) << int{id};
  ph54::set_torque(rig.bus, {1, 2, 3, 4}, true);
  ph54::ChainStateReader reader(rig.bus, std::array<std::uint8_t, 4>{1, 2, 3, 4},
                                info.fast_sync_read);
  std::array<ph54::JointReading, 4> joints;
  ASSERT_EQ(reader.read(joints), CommResult::success);
  for (const ph54::JointReading& joint : joints) {
    EXPECT_EQ(joint.current_mA, 0.0);
    EXPECT_EQ(joint.velocity_rad_s, 0.0);
  }
}

TEST(DxlEmulatedBus, VelocityModeSetUpClearsAStaleGoalVelocity) {
  PipeRig rig;
  std::array<std::uint8_t, 4> stale{};
  put_le(stale, 1000);  // 10 rev/min left by an earlier session (the motor stayed powered)
  StatusError error{};
  ASSERT_EQ(rig.bus.write(2, ph54::goal_velocity, stale, error), CommResult::success);
  ASSERT_EQ(rig.emulator.register_value(2, ph54::goal_velocity, 4), 1000u);
  ph54::ChainConfig config;
  config.mode = ph54::OperatingMode::velocity;
  ph54::set_up_chain(rig.bus, config);
  EXPECT_EQ(rig.emulator.register_value(2, ph54::goal_velocity, 4), 0u);
  EXPECT_NE(rig.emulator.register_value(2, ph54::goal_current, 2), 0u);  // still the limit
}

// A late status left in the host's input (here a Fast Sync Read status with the values of the
// flaky failure) must not be taken for the answer to the next request: send() discards it.
TEST(DxlEmulatedBus, StaleStatusInTheInputIsNotTakenForTheFastSyncReadAnswer) {
  PipeRig rig;
  const ph54::ChainInfo info = ph54::set_up_chain(rig.bus, {});
  const std::uint8_t ids[] = {1, 2, 3, 4};
  std::array<std::uint8_t, 4 * ph54::kStateLength> data{};
  for (std::size_t k = 0; k < 4; ++k)
    put_le(std::span(data).subspan(k * ph54::kStateLength, 2), 16717);
  const std::array<StatusError, 4> errors{};
  std::array<std::uint8_t, kMaxPacketBytes> stale;
  const std::size_t n = build_fast_sync_read(ph54::kStateLength, ids, data, errors, stale);
  ASSERT_GT(n, 0u);
  ASSERT_TRUE(rig.pipe.b().write(std::span(stale).first(n), serial::monotonic_now() + 1'000'000));
  ph54::ChainStateReader reader(rig.bus, ids, info.fast_sync_read);
  std::array<ph54::JointReading, 4> joints;
  ASSERT_EQ(reader.read(joints), CommResult::success);
  for (const ph54::JointReading& joint : joints)
    EXPECT_EQ(joint.current_mA, 0.0);  // torque off: the emulator's answer, not the stale one
  EXPECT_EQ(rig.bus.counters().garbage_bytes, 0u);
}

TEST(DxlEmulatedBus, EepromWriteWithTorqueOnIsAnAccessError) {
  PipeRig rig;
  ph54::set_up_chain(rig.bus, {});
  ph54::set_torque(rig.bus, {1}, true);
  StatusError error{};
  const std::uint8_t rdt[] = {10};
  ASSERT_EQ(rig.bus.write(1, ph54::return_delay_time, rdt, error), CommResult::success);
  EXPECT_EQ(error.number(), StatusError::access);
  EXPECT_THROW(ph54::write_baud_rate(rig.bus, {1}, ph54::BaudCode::b4M), Error);
}

TEST(DxlEmulatedBus, BaudRateIsWrittenWithTorqueOff) {
  PipeRig rig;
  ph54::set_up_chain(rig.bus, {});
  ph54::write_baud_rate(rig.bus, {1, 2, 3, 4}, ph54::BaudCode::b4M);
  for (std::uint8_t id = 1; id <= 4; ++id)
    EXPECT_EQ(rig.emulator.register_value(id, ph54::baud_rate, 1), 6u);
  EXPECT_EQ(ph54::baud_rate_of(ph54::BaudCode::b4M), 4'000'000);
}

TEST(DxlEmulatedBus, CorruptCrcIsCountedAndTheNextReadWorks) {
  PipeRig rig;
  const ph54::ChainInfo info = ph54::set_up_chain(rig.bus, {});
  ph54::ChainStateReader reader(rig.bus, std::array<std::uint8_t, 4>{1, 2, 3, 4},
                                info.fast_sync_read);
  std::array<ph54::JointReading, 4> joints;
  rig.emulator.corrupt_next_responses(1);
  EXPECT_EQ(reader.read(joints), CommResult::rx_corrupt);
  EXPECT_EQ(rig.bus.counters().crc_errors, 1u);
  EXPECT_EQ(reader.read(joints), CommResult::success);
}

TEST(DxlEmulatedBus, SilentMotorTimesOutAndIsCounted) {
  PipeRig rig;
  const ph54::ChainInfo info = ph54::set_up_chain(rig.bus, {});
  const std::uint8_t ids[] = {1, 2, 3, 4};
  std::array<ph54::JointReading, 4> joints;
  rig.emulator.set_silent(3, true);
  ph54::ChainStateReader fast(rig.bus, ids, info.fast_sync_read);
  ph54::ChainStateReader slow(rig.bus, ids, false);
  const serial::MonoNs start = serial::monotonic_now();
  EXPECT_EQ(fast.read(joints), CommResult::rx_timeout);       // cut-off packet
  EXPECT_EQ(slow.read(joints), CommResult::rx_timeout);       // status of ID 3 missing
  EXPECT_LT(serial::monotonic_now() - start, 2'000'000'000);  // bounded by the deadlines
  EXPECT_EQ(rig.bus.counters().timeouts, 2u);
  rig.emulator.set_silent(3, false);
  EXPECT_EQ(fast.read(joints), CommResult::success);
}

TEST(DxlEmulatedBus, AlertBitAndHardwareErrorStatus) {
  PipeRig rig;
  const ph54::ChainInfo info = ph54::set_up_chain(rig.bus, {});
  ph54::set_torque(rig.bus, {2}, true);
  rig.emulator.raise_hardware_error(2, ph54::overload);
  ph54::ChainStateReader reader(rig.bus, std::array<std::uint8_t, 4>{1, 2, 3, 4},
                                info.fast_sync_read);
  std::array<ph54::JointReading, 4> joints;
  ASSERT_EQ(reader.read(joints), CommResult::success);
  EXPECT_FALSE(joints[0].error.alert());
  EXPECT_TRUE(joints[1].error.alert());
  EXPECT_GE(rig.bus.counters().alerts, 1u);
  std::uint8_t bits = 0;
  ASSERT_TRUE(ph54::read_hardware_error(rig.bus, 2, bits));
  EXPECT_EQ(bits, ph54::overload);
  EXPECT_EQ(rig.emulator.register_value(2, ph54::torque_enable, 1), 0u);  // shut down
  StatusError error{};
  ASSERT_EQ(rig.bus.reboot(2, error), CommResult::success);
  ASSERT_EQ(reader.read(joints), CommResult::success);
  EXPECT_FALSE(joints[1].error.alert());
}

TEST(DxlEmulatedBus, BusWatchdogTripsAndLocksGoals) {
  PipeRig rig;
  ph54::ChainConfig config;
  config.ids = {1};
  config.bus_watchdog_20ms = 1;  // 20 ms
  ph54::set_up_chain(rig.bus, config);
  ph54::set_torque(rig.bus, {1}, true);
  const timespec idle{0, 80'000'000};
  clock_nanosleep(CLOCK_MONOTONIC, 0, &idle, nullptr);
  StatusError error{};
  const std::uint8_t goal[] = {10, 0};
  ASSERT_EQ(rig.bus.write(1, ph54::goal_current, goal, error), CommResult::success);
  EXPECT_EQ(error.number(), StatusError::data_range);
  EXPECT_EQ(rig.emulator.register_value(1, ph54::bus_watchdog, 1), 0xFFu);
}

TEST(DxlEmulatedBus, PtySerialPortWithSplitWritesAndGarbage) {
  serial::PtyPair pty;
  FirstOrderPlant plant(4);
  MotorChainEmulator emulator(pty.master(), plant, emu::arm_chain());
  emulator.start();
  serial::SerialPortInfo port_info;
  serial::FdTransport port = serial::open_serial_port(pty.slave_path(), 4'000'000, &port_info);
  EXPECT_FALSE(port_info.custom_baud);
  Bus bus(port, kTestTiming);
  const ph54::ChainInfo info = ph54::set_up_chain(bus, {});
  ph54::ChainStateReader reader(bus, std::array<std::uint8_t, 4>{1, 2, 3, 4}, info.fast_sync_read);
  std::array<ph54::JointReading, 4> joints;
  emulator.split_responses(true);
  emulator.garbage_before_next_response(7);
  EXPECT_EQ(reader.read(joints), CommResult::success);
  EXPECT_EQ(bus.counters().garbage_bytes, 7u);
  emulator.stop();
}

TEST(DxlSerialPort, CustomBaudGoesThroughBother) {
  serial::PtyPair pty;
  serial::SerialPortInfo info;
  serial::FdTransport port = serial::open_serial_port(pty.slave_path(), 4'500'000, &info);
  EXPECT_TRUE(port.is_open());
  EXPECT_TRUE(info.custom_baud);
  EXPECT_FALSE(info.low_latency);  // a pty refuses TIOCSSERIAL: ignored
  EXPECT_THROW(serial::open_serial_port("/nonexistent/ttyUSB9", 4'000'000), Error);
}

}  // namespace
}  // namespace tpf::dxl
