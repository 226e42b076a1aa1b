#include "dynamixel/bus/bus.hpp"

#include <algorithm>

#include "dynamixel/protocol/fast_sync_read.hpp"
#include "dynamixel/protocol/instructions.hpp"
#include "dynamixel/protocol/packet_builder.hpp"

namespace tpf::dxl {

using serial::MonoNs;
using serial::monotonic_now;

const char* to_string(CommResult result) noexcept {
  switch (result) {
    case CommResult::success:
      return "success";
    case CommResult::tx_fail:
      return "tx fail";
    case CommResult::rx_timeout:
      return "rx timeout";
    case CommResult::rx_corrupt:
      return "rx corrupt (CRC)";
    case CommResult::rx_fail:
      return "rx fail (disconnected)";
    case CommResult::bad_status:
      return "bad status packet";
  }
  return "?";
}

MonoNs BusTiming::timeout(std::size_t tx_bytes, std::size_t rx_bytes) const noexcept {
  const double wire_ms = 1e3 * 10.0 * static_cast<double>(tx_bytes + rx_bytes) / baud;
  return serial::ms_to_ns(wire_ms + turnaround_ms + margin_ms);
}

CommResult Bus::count(CommResult result) noexcept {
  ++counters_.transactions;
  switch (result) {
    case CommResult::tx_fail:
      ++counters_.tx_failures;
      break;
    case CommResult::rx_timeout:
      ++counters_.timeouts;
      break;
    case CommResult::rx_corrupt:
      ++counters_.crc_errors;
      break;
    case CommResult::rx_fail:
      ++counters_.disconnects;
      break;
    case CommResult::bad_status:
      ++counters_.bad_status;
      break;
    case CommResult::success:
      break;
  }
  return result;
}

void Bus::count_status(StatusError error) noexcept {
  if (error.number() != StatusError::none) ++counters_.status_errors;
  if (error.alert()) ++counters_.alerts;
}

bool Bus::send(std::size_t n, MonoNs deadline) noexcept {
  if (n == 0) return false;
  port_.discard_input();  // as SDK clearPort() before every transmit
  rx_.clear();
  return port_.write(std::span(tx_).first(n), deadline);
}

CommResult Bus::receive(std::uint8_t id, bool unstuff, MonoNs deadline) noexcept {
  for (;;) {
    const std::size_t garbage_before = rx_.dropped_bytes();
    const RxEvent event = rx_.next();
    counters_.garbage_bytes += rx_.dropped_bytes() - garbage_before;
    if (event == RxEvent::corrupt) return CommResult::rx_corrupt;
    if (event == RxEvent::packet) {
      if (!decode_packet(rx_.packet(), unstuff, packet_)) return CommResult::bad_status;
      if (packet_.id == id) return CommResult::success;
      continue;  // a status from another device (e.g. a late answer): keep waiting
    }
    const serial::ReadResult r = port_.read(rx_.write_area(), deadline);
    if (r.disconnected) return CommResult::rx_fail;
    if (r.bytes == 0) return CommResult::rx_timeout;
    rx_.commit(r.bytes);
  }
}

CommResult Bus::ping(std::uint8_t id, PingInfo& info) noexcept {
  const std::size_t n = build_ping(id, tx_);
  const MonoNs deadline = monotonic_now() + timing_.timeout(n, 14);
  if (!send(n, deadline)) return count(CommResult::tx_fail);
  const CommResult r = receive(id, true, deadline);
  if (r != CommResult::success) return count(r);
  if (packet_.param_count != 3) return count(CommResult::bad_status);
  info = PingInfo{static_cast<std::uint16_t>(packet_.params[0] | (packet_.params[1] << 8)),
                  packet_.params[2], packet_.error};
  count_status(info.error);
  return count(CommResult::success);
}

CommResult Bus::read(std::uint8_t id, std::uint16_t address, std::span<std::uint8_t> data,
                     StatusError& error) noexcept {
  const std::size_t n = build_read(id, address, static_cast<std::uint16_t>(data.size()), tx_);
  const MonoNs deadline = monotonic_now() + timing_.timeout(n, 11 + data.size());
  if (!send(n, deadline)) return count(CommResult::tx_fail);
  const CommResult r = receive(id, true, deadline);
  if (r != CommResult::success) return count(r);
  error = packet_.error;
  count_status(error);
  if (packet_.param_count != data.size()) {
    // An error status carries no data.
    return count(error.number() != StatusError::none ? CommResult::success
                                                     : CommResult::bad_status);
  }
  std::copy_n(packet_.params.begin(), data.size(), data.begin());
  return count(CommResult::success);
}

CommResult Bus::write(std::uint8_t id, std::uint16_t address, std::span<const std::uint8_t> data,
                      StatusError& error) noexcept {
  const std::size_t n = build_write(id, address, data, tx_);
  const MonoNs deadline = monotonic_now() + timing_.timeout(n, 11);
  if (!send(n, deadline)) return count(CommResult::tx_fail);
  const CommResult r = receive(id, true, deadline);
  if (r == CommResult::success) {
    error = packet_.error;
    count_status(error);
  }
  return count(r);
}

CommResult Bus::reboot(std::uint8_t id, StatusError& error) noexcept {
  const std::size_t n = build_reboot(id, tx_);
  const MonoNs deadline = monotonic_now() + timing_.timeout(n, 11);
  if (!send(n, deadline)) return count(CommResult::tx_fail);
  const CommResult r = receive(id, true, deadline);
  if (r == CommResult::success) error = packet_.error;
  return count(r);
}

CommResult Bus::sync_read(std::uint16_t address, std::uint16_t length,
                          std::span<const std::uint8_t> ids, std::span<std::uint8_t> data,
                          std::span<StatusError> errors) noexcept {
  const std::size_t n = build_sync_read(Instruction::sync_read, address, length, ids, tx_);
  const MonoNs deadline = monotonic_now() + timing_.timeout(n, ids.size() * (11 + length));
  if (data.size() < ids.size() * length || errors.size() < ids.size() || !send(n, deadline))
    return count(CommResult::tx_fail);
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const CommResult r = receive(ids[k], true, deadline);
    if (r != CommResult::success) return count(r);
    errors[k] = packet_.error;
    count_status(errors[k]);
    if (packet_.param_count != length) return count(CommResult::bad_status);
    std::copy_n(packet_.params.begin(), length,
                data.begin() + static_cast<std::ptrdiff_t>(k * length));
  }
  return count(CommResult::success);
}

CommResult Bus::fast_sync_read(std::uint16_t address, std::uint16_t length,
                               std::span<const std::uint8_t> ids, std::span<std::uint8_t> data,
                               std::span<StatusError> errors) noexcept {
  const std::size_t n = build_sync_read(Instruction::fast_sync_read, address, length, ids, tx_);
  const MonoNs deadline = monotonic_now() + timing_.timeout(n, 8 + ids.size() * (length + 4));
  if (!send(n, deadline)) return count(CommResult::tx_fail);
  const CommResult r = receive(kBroadcastId, false, deadline);
  if (r != CommResult::success) return count(r);
  if (!parse_fast_sync_read(rx_.packet(), length, ids, data, errors))
    return count(CommResult::bad_status);
  for (std::size_t k = 0; k < ids.size(); ++k)
    count_status(errors[k]);
  return count(CommResult::success);
}

CommResult Bus::sync_write(std::uint16_t address, std::uint16_t length,
                           std::span<const std::uint8_t> ids,
                           std::span<const std::uint8_t> data) noexcept {
  const std::size_t n = build_sync_write(address, length, ids, data, tx_);
  const MonoNs deadline = monotonic_now() + timing_.timeout(n, 0);
  return count(send(n, deadline) ? CommResult::success : CommResult::tx_fail);
}

}  // namespace tpf::dxl
