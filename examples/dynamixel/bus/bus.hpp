// Host side of a Protocol 2.0 bus: one transaction at a time over a ByteTransport, with
// deadlines on CLOCK_MONOTONIC, fault counters and no allocation (safe in the control loop).
#pragma once

#include <cstdint>

#include "dynamixel/protocol/packet.hpp"
#include "dynamixel/protocol/packet_receiver.hpp"
#include "dynamixel/serial/byte_transport.hpp"

namespace tpf::dxl {

/// Result of a transaction, as the SDK's COMM_* codes.
enum class CommResult : std::uint8_t {
  success,
  tx_fail,     ///< write failed (COMM_TX_FAIL)
  rx_timeout,  ///< no (complete) status before the deadline (COMM_RX_TIMEOUT)
  rx_corrupt,  ///< CRC mismatch (COMM_RX_CORRUPT)
  rx_fail,     ///< the port disconnected (COMM_RX_FAIL)
  bad_status,  ///< CRC-valid but wrong ID or length
};

const char* to_string(CommResult result) noexcept;

/// Faults and traffic seen by one Bus since construction.
struct BusCounters {
  std::uint64_t transactions = 0;
  std::uint64_t timeouts = 0;
  std::uint64_t crc_errors = 0;
  std::uint64_t tx_failures = 0;
  std::uint64_t disconnects = 0;
  std::uint64_t bad_status = 0;
  std::uint64_t status_errors = 0;  ///< status packets with a non-zero error number
  std::uint64_t alerts = 0;         ///< status packets with the Alert bit
  std::uint64_t garbage_bytes = 0;  ///< bytes dropped while resynchronising
};

/// Response deadline: timeout = (tx + rx bytes)·10 bit / baud + turnaround + margin.
struct BusTiming {
  int baud = 4'000'000;
  double turnaround_ms = 1.0;  ///< USB round trip with FTDI latency timer 1 ms (hardware.md §3.3)
  double margin_ms = 1.0;

  serial::MonoNs timeout(std::size_t tx_bytes, std::size_t rx_bytes) const noexcept;
};

/// Ping status: model number and firmware version (Fast Sync Read on the P series needs ≥ 12).
struct PingInfo {
  std::uint16_t model = 0;
  std::uint8_t firmware = 0;
  StatusError error{};
};

class Bus {
 public:
  Bus(serial::ByteTransport& port, BusTiming timing) noexcept : port_(port), timing_(timing) {}

  CommResult ping(std::uint8_t id, PingInfo& info) noexcept;
  /// Reads data.size() bytes from `address` of device `id`. An error status carries no data:
  /// then the result is success, `error` holds the error number and `data` is left unchanged.
  CommResult read(std::uint8_t id, std::uint16_t address, std::span<std::uint8_t> data,
                  StatusError& error) noexcept;
  CommResult write(std::uint8_t id, std::uint16_t address, std::span<const std::uint8_t> data,
                   StatusError& error) noexcept;
  CommResult reboot(std::uint8_t id, StatusError& error) noexcept;
  /// Sync Read: one status packet per ID, in ID order. data = ids.size()·length bytes.
  CommResult sync_read(std::uint16_t address, std::uint16_t length,
                       std::span<const std::uint8_t> ids, std::span<std::uint8_t> data,
                       std::span<StatusError> errors) noexcept;
  /// Fast Sync Read: one combined status packet (firmware ≥ 12 on the P series).
  CommResult fast_sync_read(std::uint16_t address, std::uint16_t length,
                            std::span<const std::uint8_t> ids, std::span<std::uint8_t> data,
                            std::span<StatusError> errors) noexcept;
  /// Sync Write (no status returned). data = ids.size()·length bytes in ID order.
  CommResult sync_write(std::uint16_t address, std::uint16_t length,
                        std::span<const std::uint8_t> ids,
                        std::span<const std::uint8_t> data) noexcept;

  const BusCounters& counters() const noexcept { return counters_; }
  const BusTiming& timing() const noexcept { return timing_; }
  /// E.g. a generous timeout during start-up, a tight one in the loop.
  void set_timing(const BusTiming& timing) noexcept { timing_ = timing; }

 private:
  /// Clears the input, sends tx_[0..n); false (counted) on failure.
  bool send(std::size_t n, serial::MonoNs deadline) noexcept;
  /// Waits for one status packet from `id`; raw bytes in rx_.packet(), decoded in packet_.
  CommResult receive(std::uint8_t id, bool unstuff, serial::MonoNs deadline) noexcept;
  CommResult count(CommResult result) noexcept;
  void count_status(StatusError error) noexcept;

  serial::ByteTransport& port_;
  BusTiming timing_;
  PacketReceiver rx_{PacketReceiver::Accept::status};
  Packet packet_;
  std::array<std::uint8_t, kMaxPacketBytes> tx_{};
  BusCounters counters_;
};

}  // namespace tpf::dxl
