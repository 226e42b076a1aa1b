#include "dynamixel/emulator/motor_chain_emulator.hpp"

#include <algorithm>
#include <array>

#include "dynamixel/protocol/fast_sync_read.hpp"
#include "dynamixel/protocol/packet_builder.hpp"
#include "dynamixel/serial/thread_priority.hpp"
#include "tpf/common/error.hpp"

namespace tpf::dxl::emu {

using serial::MonoNs;
using serial::monotonic_now;

std::vector<EmulatedMotor> arm_chain(std::uint8_t firmware) {
  return {{1, ph54::kModelPh54_200, firmware},
          {2, ph54::kModelPh54_200, firmware},
          {3, ph54::kModelPh54_100, firmware},
          {4, ph54::kModelPh54_100, firmware}};
}

MotorChainEmulator::MotorChainEmulator(serial::ByteTransport& bus, MotorPlant& plant,
                                       std::vector<EmulatedMotor> motors)
    : bus_(bus),
      plant_(plant),
      motors_(std::move(motors)),
      goals_(motors_.size()),
      silent_(motors_.size(), 0) {
  if (plant_.joints() != motors_.size())
    throw Error::at("MotorChainEmulator", 0, "plant", "joint count differs from motor count");
  for (const EmulatedMotor& m : motors_)
    registers_.emplace_back(m.id, m.model, m.firmware);
}

MotorChainEmulator::~MotorChainEmulator() {
  stop();
}

void MotorChainEmulator::start(int realtime_priority) {
  if (running_.exchange(true)) return;
  boot_ns_ = last_step_ns_ = last_instruction_ns_ = monotonic_now();
  thread_ = std::thread([this, realtime_priority] {
    serial::set_current_thread_fifo(realtime_priority);
    run();
  });
}

void MotorChainEmulator::stop() {
  running_.store(false);
  if (thread_.joinable()) thread_.join();
}

int MotorChainEmulator::index_of(std::uint8_t id) const {
  for (std::size_t k = 0; k < motors_.size(); ++k)
    if (motors_[k].id == id) return static_cast<int>(k);
  return -1;
}

void MotorChainEmulator::set_silent(std::uint8_t id, bool silent) {
  std::lock_guard lock(mutex_);
  if (const int k = index_of(id); k >= 0) silent_[k] = silent;
}

void MotorChainEmulator::raise_hardware_error(std::uint8_t id, std::uint8_t bits) {
  std::lock_guard lock(mutex_);
  if (const int k = index_of(id); k >= 0) registers_[k].raise_hardware_error(bits);
}

std::uint32_t MotorChainEmulator::register_value(std::uint8_t id, std::uint16_t address,
                                                 std::size_t size) {
  std::lock_guard lock(mutex_);
  const int k = index_of(id);
  return k < 0 ? 0 : registers_[k].u32(address, size);
}

void MotorChainEmulator::advance_plant() {
  const MonoNs now = monotonic_now();
  while (now - last_step_ns_ > 0) {  // ≤ 1 ms sub-steps
    const MonoNs dt = std::min<MonoNs>(now - last_step_ns_, 1'000'000);
    for (std::size_t k = 0; k < motors_.size(); ++k)
      goals_[k] = registers_[k].goal();
    plant_.step(static_cast<double>(dt) * 1e-9, goals_);
    last_step_ns_ += dt;
  }
  const auto tick = static_cast<std::uint16_t>(((now - boot_ns_) / 1'000'000) % 32768);
  const double idle = static_cast<double>(now - last_instruction_ns_) * 1e-9;
  for (std::size_t k = 0; k < motors_.size(); ++k) {
    registers_[k].set_present(plant_.state(k), tick);
    registers_[k].check_watchdog(idle);
  }
}

void MotorChainEmulator::run() {
  while (running_.load(std::memory_order_relaxed)) {
    const serial::ReadResult r = bus_.read(rx_.write_area(), monotonic_now() + 1'000'000);
    if (r.disconnected) break;
    rx_.commit(r.bytes);
    std::lock_guard lock(mutex_);
    advance_plant();
    for (RxEvent e = rx_.next(); e != RxEvent::need_more; e = rx_.next()) {
      if (e == RxEvent::packet && decode_packet(rx_.packet(), true, packet_)) {
        last_instruction_ns_ = monotonic_now();
        instructions_.fetch_add(1);
        handle(packet_);
      }
    }
  }
}

void MotorChainEmulator::reply(std::span<const std::uint8_t> bytes) {
  std::array<std::uint8_t, kMaxPacketBytes + 64> out;
  std::size_t n = 0;
  for (int g = garbage_.exchange(0); g > 0 && n < 64; --g)
    out[n++] = static_cast<std::uint8_t>(0x5A + g);
  std::copy(bytes.begin(), bytes.end(), out.begin() + static_cast<std::ptrdiff_t>(n));
  n += bytes.size();
  if (corrupt_.load() > 0) {
    corrupt_.fetch_sub(1);
    out[n - 1] ^= 0x01;
  }
  const MonoNs deadline = monotonic_now() + 50'000'000;
  if (!split_.load()) {
    bus_.write(std::span(out).first(n), deadline);
    return;
  }
  for (std::size_t at = 0; at < n; at += 3) {
    bus_.write(std::span(out).subspan(at, std::min<std::size_t>(3, n - at)), deadline);
    const timespec pause{0, 20'000};
    clock_nanosleep(CLOCK_MONOTONIC, 0, &pause, nullptr);
  }
}

void MotorChainEmulator::return_delay(std::size_t k) {
  const long ns = 2'000L * registers_[k].u8(ph54::return_delay_time);  // 2 µs units
  if (ns <= 0) return;
  const timespec delay{0, ns};
  clock_nanosleep(CLOCK_MONOTONIC, 0, &delay, nullptr);
}

void MotorChainEmulator::send_status(std::size_t k, StatusError error,
                                     std::span<const std::uint8_t> params) {
  if (silent_[k]) return;
  std::array<std::uint8_t, kMaxPacketBytes> out;
  return_delay(k);
  reply(std::span(out).first(build_status(motors_[k].id, error, params, out)));
}

namespace {

std::uint16_t u16_at(std::span<const std::uint8_t> params, std::size_t at) {
  return static_cast<std::uint16_t>(params[at] | (params[at + 1] << 8));
}

}  // namespace

void MotorChainEmulator::handle(const Packet& p) {
  switch (p.instruction) {
    case Instruction::ping:
      return on_ping(p.id);
    case Instruction::read:
    case Instruction::write:
    case Instruction::reboot:
      return on_unicast(p);
    case Instruction::sync_write:
      return on_sync_write(p.parameters());
    case Instruction::sync_read:
      return on_sync_read(p.parameters());
    case Instruction::fast_sync_read:
      return on_fast_sync_read(p.parameters());
    default:
      if (const int k = index_of(p.id); k >= 0) send_status(k, {StatusError::instruction}, {});
      return;
  }
}

void MotorChainEmulator::on_ping(std::uint8_t id) {
  for (std::size_t k = 0; k < motors_.size(); ++k) {
    if (id != kBroadcastId && motors_[k].id != id) continue;
    const std::uint8_t info[] = {static_cast<std::uint8_t>(motors_[k].model & 0xFF),
                                 static_cast<std::uint8_t>(motors_[k].model >> 8),
                                 motors_[k].firmware};
    send_status(k, registers_[k].alert_bits(), info);
  }
}

void MotorChainEmulator::on_unicast(const Packet& p) {
  const int k = index_of(p.id);
  if (k < 0) return;
  const auto params = p.parameters();
  if (p.instruction == Instruction::reboot) {
    registers_[k].reboot();
    send_status(k, {}, {});
  } else if (p.instruction == Instruction::read) {
    if (params.size() != 4 || u16_at(params, 2) > data_.size())
      return send_status(k, {StatusError::data_length}, {});
    const auto out = std::span(data_).first(u16_at(params, 2));
    const StatusError e = registers_[k].read(u16_at(params, 0), out);
    send_status(k, e, e.number() == StatusError::none ? out : std::span<std::uint8_t>{});
  } else {  // write
    if (params.size() < 3) return send_status(k, {StatusError::data_length}, {});
    send_status(k, registers_[k].write(u16_at(params, 0), params.subspan(2)), {});
  }
}

void MotorChainEmulator::on_sync_write(std::span<const std::uint8_t> params) {
  if (params.size() < 4) return;
  const std::uint16_t address = u16_at(params, 0), length = u16_at(params, 2);
  for (std::size_t at = 4; at + 1 + length <= params.size(); at += 1 + length)
    if (const int k = index_of(params[at]); k >= 0)
      registers_[k].write(address, params.subspan(at + 1, length));
}

void MotorChainEmulator::on_sync_read(std::span<const std::uint8_t> params) {
  if (params.size() < 5 || u16_at(params, 2) > data_.size()) return;
  const auto out = std::span(data_).first(u16_at(params, 2));
  for (const std::uint8_t id : params.subspan(4))  // each motor answers in list order
    if (const int k = index_of(id); k >= 0)
      send_status(k, registers_[k].read(u16_at(params, 0), out), out);
}

void MotorChainEmulator::on_fast_sync_read(std::span<const std::uint8_t> params) {
  if (params.size() < 5) return;
  const std::uint16_t address = u16_at(params, 0), length = u16_at(params, 2);
  const auto ids = params.subspan(4);
  std::array<StatusError, kMaxChain> errors{};
  if (ids.size() > errors.size() || ids.size() * length > data_.size()) return;
  // One combined packet; it ends where a listed motor is missing, silent or on old firmware.
  std::size_t answered = 0;
  for (; answered < ids.size(); ++answered) {
    const int k = index_of(ids[answered]);
    if (k < 0 || silent_[k] || motors_[k].firmware < ph54::kFastSyncReadMinFirmware) break;
    errors[answered] =
        registers_[k].read(address, std::span(data_).subspan(answered * length, length));
  }
  if (answered == 0) return;
  std::array<std::uint8_t, kMaxPacketBytes> out;
  const std::size_t n =
      build_fast_sync_read(length, ids, std::span(data_).first(ids.size() * length),
                           std::span(errors).first(ids.size()), out);
  if (n == 0) return;
  return_delay(0);
  reply(std::span(out).first(answered == ids.size() ? n : 8 + answered * (length + 4u)));
}

}  // namespace tpf::dxl::emu
