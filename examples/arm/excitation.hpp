// Excitation trajectory for identification logs: a ramped multisine per joint around its start
// position, q_goal_j(t) = q0_j + r(t)·(A/3)·Σ_{m=1..3} sin(2π·c_m·f_j·t),
// f_j = 0.1·(j+1) Hz, c = {1, 2.3, 4.1} (no shared harmonics), r(t) = min(t/2 s, 1).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>

namespace tpf::arm {

/// Goal position of joint j (0-based) at time t [s] for amplitude A [rad] around q0 [rad].
inline double excitation_goal(std::size_t j, double t, double amplitude, double q0) noexcept {
  constexpr double kRatios[] = {1.0, 2.3, 4.1};
  const double f = 0.1 * static_cast<double>(j + 1);
  double sum = 0.0;
  for (const double c : kRatios)
    sum += std::sin(2.0 * std::numbers::pi * c * f * t);
  return q0 + std::min(t / 2.0, 1.0) * amplitude / 3.0 * sum;
}

}  // namespace tpf::arm
