// The contact-free excitation reference (scenario kind "excitation"): each joint alternates rests
// of random length and minimum-jerk moves of random size, sign and speed inside its range, so
// motion onsets happen in both directions at many poses and gravity loads (the TCN trains on it).
#pragma once

#include "offline/sim/min_jerk_schedule.hpp"
#include "offline/sim/random.hpp"
#include "offline/sim/scenario.hpp"

namespace tpf::offline {

/// Builds the schedule from `start` until `duration` (s). `lower`/`upper` already intersected
/// with the joint limits. A move that would leave the range is reflected (its sign flipped).
MinJerkSchedule make_excitation_schedule(const ExcitationConfig& config, const TwinVector& start,
                                         const TwinVector& lower, const TwinVector& upper,
                                         double duration, Random& rng);

}  // namespace tpf::offline
