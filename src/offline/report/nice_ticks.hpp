// "Nice" axis ticks: steps of 1, 2 or 5 times a power of ten (Heckbert, Graphics Gems, 1990).
#pragma once

#include <vector>

namespace tpf::offline {

struct Ticks {
  double lo = 0.0;             ///< axis start: a multiple of step at or below the data minimum
  double hi = 1.0;             ///< axis end: a multiple of step at or above the data maximum
  double step = 0.2;           ///< 1, 2 or 5 · 10^k
  std::vector<double> values;  ///< lo, lo + step, ..., hi (multiples of step, exact zero kept)
  int decimals = 1;  ///< decimals that show every tick distinctly: max(0, −floor(log10 step))
};

/// Ticks covering [min, max] with about `target` intervals. A degenerate range (min == max) is
/// widened by ±max(|min|·10 %, 1); non-finite input gives [0, 1]. Throws nothing.
Ticks nice_ticks(double min, double max, int target = 5);

/// 1, 2, 5 or 10 times 10^floor(log10 x): the nice number nearest x (round) or at or above it.
double nice_number(double x, bool round);

}  // namespace tpf::offline
