#include "dynamixel/ph54/chain_state_reader.hpp"

#include <algorithm>

#include "dynamixel/ph54/control_table.hpp"
#include "dynamixel/ph54/units.hpp"

namespace tpf::dxl::ph54 {

ChainStateReader::ChainStateReader(Bus& bus, std::span<const std::uint8_t> ids, bool fast) noexcept
    : bus_(bus), count_(std::min(ids.size(), kMaxChainMotors)), fast_(fast) {
  std::copy_n(ids.begin(), count_, ids_.begin());
}

CommResult ChainStateReader::read(std::span<JointReading> out) noexcept {
  const auto ids = std::span(ids_).first(count_);
  const auto data = std::span(data_).first(count_ * kStateLength);
  const auto errors = std::span(errors_).first(count_);
  const CommResult r = fast_ ? bus_.fast_sync_read(kStateAddress, kStateLength, ids, data, errors)
                             : bus_.sync_read(kStateAddress, kStateLength, ids, data, errors);
  if (r != CommResult::success) return r;
  for (std::size_t k = 0; k < count_ && k < out.size(); ++k) {
    const auto block = data.subspan(k * kStateLength, kStateLength);
    out[k].current_mA = static_cast<std::int16_t>(get_le(block.subspan(0, 2)));
    out[k].velocity_rad_s =
        velocity_to_rad_s(static_cast<std::int32_t>(get_le(block.subspan(2, 4))));
    out[k].position_rad = position_to_rad(static_cast<std::int32_t>(get_le(block.subspan(6, 4))));
    out[k].error = errors[k];
  }
  return r;
}

}  // namespace tpf::dxl::ph54
