// Candidate: ripple periodic in the joint (output) angle, n periods per revolution of q (the
// run-time PositionRipple, output side).
#pragma once

#include "offline/effects/ripple_columns.hpp"

namespace tpf::offline {

struct OutputRippleColumns : RippleColumns<false> {
  static constexpr std::string_view key = "ripple";
  /// A few periods over the joint's range of q: its phase outside the range is extrapolated (the
  /// motor-side ripple has G times as many periods, all seen within any range).
  static constexpr bool kExtrapolatesInQ = true;
};

}  // namespace tpf::offline
