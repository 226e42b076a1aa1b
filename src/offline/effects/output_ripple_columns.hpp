// Candidate: ripple periodic in the joint (output) angle, n periods per revolution of q (the
// run-time PositionRipple, output side).
#pragma once

#include "offline/effects/ripple_columns.hpp"

namespace tpf::offline {

struct OutputRippleColumns : RippleColumns<false> {
  static constexpr std::string_view key = "ripple";
};

}  // namespace tpf::offline
