// Pneumatic skin pads as the Teensy reports them (hardware.md §4), run at 1 kHz:
//   τ_p·ṗ = gain(A)·F_n − p,   gain(A) = g_ref·(A_ref/A)^γ      (kPa; F_n ≥ 0 pushes into the pad)
//   reading = clamp(quantise(p + offset + noise), 0, full scale),  offset a random walk.
// A pad reports only the normal push, never shear or pull, and its gain depends on the unknown
// contact area A, so the pressure gives the force magnitude only roughly.
#pragma once

#include <vector>

#include "offline/sim/random.hpp"
#include "offline/sim/scenario.hpp"

namespace tpf::offline {

class PadSensors {
 public:
  PadSensors(const PadSensorConfig& config, int pad_count, Random rng);

  /// Advances every pad by dt with normal force F_n (N, negative = pull, seen as 0) and contact
  /// area (cm²) per pad, then samples them.
  void update(const std::vector<double>& normal_force, const std::vector<double>& area_cm2,
              double dt);

  /// Latest reading of pad k (0-based), kPa gauge.
  double reading(int k) const { return reading_[k]; }
  int count() const { return static_cast<int>(reading_.size()); }

 private:
  PadSensorConfig config_;
  Random rng_;
  std::vector<double> pressure_, offset_, reading_;
};

}  // namespace tpf::offline
