#include "offline/sim/excitation_schedule.hpp"

#include <algorithm>
#include <cmath>

namespace tpf::offline {

MinJerkSchedule make_excitation_schedule(const ExcitationConfig& c, const TwinVector& start,
                                         const TwinVector& lower, const TwinVector& upper,
                                         double duration, Random& rng) {
  MinJerkSchedule schedule(start);
  constexpr double kMinMoveTime = 0.15;  // s
  for (int j = 0; j < start.size(); ++j) {
    while (schedule.end_time(j) < duration) {
      const double q0 = schedule.end_position(j);
      schedule.append(j, q0, rng.uniform(c.rest_min_s, c.rest_max_s));
      double delta = rng.sign() * rng.uniform(c.move_min_rad, c.move_max_rad);
      if (q0 + delta > upper[j] || q0 + delta < lower[j]) delta = -delta;
      const double q1 = std::clamp(q0 + delta, lower[j], upper[j]);
      const double speed = rng.uniform(c.speed_min, c.speed_max);
      schedule.append(j, q1, std::max(kMinMoveTime, 1.875 * std::abs(q1 - q0) / speed));
    }
  }
  return schedule;
}

}  // namespace tpf::offline
