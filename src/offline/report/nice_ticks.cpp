#include "offline/report/nice_ticks.hpp"

#include <algorithm>
#include <cmath>

namespace tpf::offline {

double nice_number(double x, bool round) {
  const double exponent = std::floor(std::log10(x));
  const double power = std::pow(10.0, exponent);
  const double fraction = x / power;
  double nice = 10.0;
  if (round) {
    nice = fraction < 1.5 ? 1.0 : fraction < 3.0 ? 2.0 : fraction < 7.0 ? 5.0 : 10.0;
  } else {
    nice = fraction <= 1.0 ? 1.0 : fraction <= 2.0 ? 2.0 : fraction <= 5.0 ? 5.0 : 10.0;
  }
  return nice * power;
}

Ticks nice_ticks(double min, double max, int target) {
  if (!std::isfinite(min) || !std::isfinite(max)) min = 0.0, max = 1.0;
  if (min > max) std::swap(min, max);
  if (min == max) {
    const double widen = std::max(std::abs(min) * 0.1, 1.0);
    min -= widen;
    max += widen;
  }
  target = std::max(target, 2);
  Ticks ticks;
  const double range = nice_number(max - min, false);
  ticks.step = nice_number(range / target, true);
  ticks.lo = std::floor(min / ticks.step + 1e-9) * ticks.step;
  ticks.hi = std::ceil(max / ticks.step - 1e-9) * ticks.step;
  const long count = std::lround((ticks.hi - ticks.lo) / ticks.step);
  for (long i = 0; i <= count; ++i) {
    double v = ticks.lo + static_cast<double>(i) * ticks.step;
    if (std::abs(v) < 1e-9 * ticks.step) v = 0.0;
    ticks.values.push_back(v);
  }
  ticks.decimals = std::max(0, -static_cast<int>(std::floor(std::log10(ticks.step) + 1e-9)));
  return ticks;
}

}  // namespace tpf::offline
