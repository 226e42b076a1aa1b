#include "offline/sim/pad_sensors.hpp"

#include <algorithm>
#include <cmath>

namespace tpf::offline {

PadSensors::PadSensors(const PadSensorConfig& config, int pad_count, Random rng)
    : config_(config),
      rng_(std::move(rng)),
      pressure_(pad_count, 0.0),
      offset_(pad_count, 0.0),
      reading_(pad_count, 0.0) {
  for (double& o : offset_)
    o = rng_.uniform(0.05, 0.3);  // zero offset after calibration
}

void PadSensors::update(const std::vector<double>& normal_force,
                        const std::vector<double>& area_cm2, double dt) {
  const double decay = std::exp(-dt / config_.time_constant_s);
  const double drift = config_.drift_kpa_per_sqrt_s * std::sqrt(dt);
  for (std::size_t k = 0; k < pressure_.size(); ++k) {
    const double force = std::max(0.0, normal_force[k]);
    const double area = std::max(area_cm2[k], 1e-3);
    const double gain =
        config_.gain_kpa_per_n * std::pow(config_.reference_area_cm2 / area, config_.area_exponent);
    const double target = gain * force;
    pressure_[k] = target + (pressure_[k] - target) * decay;
    offset_[k] += drift * rng_.normal();
    double p = pressure_[k] + offset_[k] + config_.noise_kpa * rng_.normal();
    if (config_.adc_step_kpa > 0) p = std::round(p / config_.adc_step_kpa) * config_.adc_step_kpa;
    // Reported with 0.1 Pa resolution, so the log shows 0.21 rather than 0.21000000000000002.
    reading_[k] = std::round(std::clamp(p, 0.0, config_.full_scale_kpa) * 1e4) / 1e4;
  }
}

}  // namespace tpf::offline
