// A chain of emulated PH54 motors on one bus (a pty master or an in-memory pipe): answers Ping,
// Read, Write, Reboot, Sync Read, Fast Sync Read and Sync Write with the control-table semantics
// the host uses, advances a MotorPlant in real time, and injects faults on request.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#include "dynamixel/emulator/motor_plant.hpp"
#include "dynamixel/emulator/ph54_registers.hpp"
#include "dynamixel/protocol/packet_receiver.hpp"
#include "dynamixel/serial/byte_transport.hpp"
#include "dynamixel/serial/monotonic_clock.hpp"

namespace tpf::dxl::emu {

struct EmulatedMotor {
  std::uint8_t id = 1;
  std::uint16_t model = ph54::kModelPh54_200;
  std::uint8_t firmware = 12;  ///< < 12: Fast Sync Read is ignored, as on old firmware
};

/// The arm's default chain: IDs 1–4, PH54-200 on joints 1–2 and PH54-100 on joints 3–4.
std::vector<EmulatedMotor> arm_chain(std::uint8_t firmware = 12);

class MotorChainEmulator {
 public:
  /// `plant.joints()` must equal motors.size(); joint k is motors[k]. Both must outlive this.
  MotorChainEmulator(serial::ByteTransport& bus, MotorPlant& plant,
                     std::vector<EmulatedMotor> motors);
  ~MotorChainEmulator();
  MotorChainEmulator(const MotorChainEmulator&) = delete;
  MotorChainEmulator& operator=(const MotorChainEmulator&) = delete;

  /// Starts the device thread; priority > 0 asks for SCHED_FIFO (best effort).
  void start(int realtime_priority = 0);
  void stop();

  // Fault injection (any thread).
  /// The next n responses go out with a wrong CRC.
  void corrupt_next_responses(int n) noexcept { corrupt_.fetch_add(n); }
  /// Responses are written in 3-byte pieces with 20 µs pauses (partial reads on the host).
  void split_responses(bool on) noexcept { split_.store(on); }
  /// `n` bytes of noise precede the next response.
  void garbage_before_next_response(int n) noexcept { garbage_.fetch_add(n); }
  /// Motor `id` stops answering (Fast Sync Read responses are cut off at its block).
  void set_silent(std::uint8_t id, bool silent);
  /// Hardware error on motor `id` (Overload, …): Alert bit on every status until Reboot.
  void raise_hardware_error(std::uint8_t id, std::uint8_t bits);
  /// Reads a register of motor `id` (inspection in tests).
  std::uint32_t register_value(std::uint8_t id, std::uint16_t address, std::size_t size);
  std::uint64_t instructions_seen() const noexcept { return instructions_.load(); }
  /// CLOCK_MONOTONIC [ns] at start(): the plant's time 0 (it is advanced in real time).
  serial::MonoNs boot_ns() const noexcept { return boot_ns_; }

 private:
  void run();
  void advance_plant();
  void handle(const Packet& p);
  void on_ping(std::uint8_t id);
  void on_unicast(const Packet& p);  ///< Read, Write, Reboot
  void on_sync_write(std::span<const std::uint8_t> params);
  void on_sync_read(std::span<const std::uint8_t> params);
  void on_fast_sync_read(std::span<const std::uint8_t> params);
  void reply(std::span<const std::uint8_t> bytes);
  void send_status(std::size_t k, StatusError error, std::span<const std::uint8_t> params);
  void return_delay(std::size_t k);
  int index_of(std::uint8_t id) const;

  serial::ByteTransport& bus_;
  MotorPlant& plant_;
  std::vector<EmulatedMotor> motors_;
  std::vector<Ph54Registers> registers_;
  std::vector<MotorGoal> goals_;
  std::vector<std::uint8_t> silent_;
  std::mutex mutex_;  // guards registers_, silent_ and the plant against the test thread
  PacketReceiver rx_{PacketReceiver::Accept::instructions};
  Packet packet_;
  std::array<std::uint8_t, kMaxParams - 1> data_{};  ///< read-back buffer of one response
  static constexpr std::size_t kMaxChain = 64;
  std::int64_t boot_ns_ = 0, last_step_ns_ = 0, last_instruction_ns_ = 0;
  std::atomic<int> corrupt_{0}, garbage_{0};
  std::atomic<bool> split_{false}, running_{false};
  std::atomic<std::uint64_t> instructions_{0};
  std::thread thread_;
};

}  // namespace tpf::dxl::emu
