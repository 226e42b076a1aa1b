// Candidate: ripple periodic in the motor angle G·q, n periods per motor revolution (the run-time
// PositionRipple, motor side).
#pragma once

#include "offline/effects/ripple_columns.hpp"

namespace tpf::offline {

struct MotorRippleColumns : RippleColumns<true> {
  static constexpr std::string_view key = "ripple_motor";
};

}  // namespace tpf::offline
