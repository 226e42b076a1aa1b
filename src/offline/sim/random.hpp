// Reproducible random numbers for the digital twin: std::mt19937_64 plus our own distributions,
// because the standard library's distributions differ between implementations. The same seed
// gives the same sequence on every platform, so the same seed gives the same log bit for bit.
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace tpf::offline {

class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  /// Uniform on [0, 1): the top 53 bits of one engine draw.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform on [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Standard normal by the Box–Muller transform (both values used, so one draw per two calls).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = 1.0 - uniform();  // (0, 1]
    const double u2 = uniform();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * std::numbers::pi * u2);
  }
  /// Normal with mean m and standard deviation s.
  double normal(double m, double s) { return m + s * normal(); }
  /// True with probability p.
  bool chance(double p) { return uniform() < p; }
  /// ±1 with equal probability.
  double sign() { return uniform() < 0.5 ? -1.0 : 1.0; }
  /// Integer uniform on [0, n).
  int index(int n) { return static_cast<int>(uniform() * n); }
  /// An independent stream for one subsystem, derived from this one.
  Random split() { return Random(engine_() ^ 0x9E3779B97F4A7C15ull); }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace tpf::offline
