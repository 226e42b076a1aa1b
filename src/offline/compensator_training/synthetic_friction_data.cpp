#include "offline/compensator_training/synthetic_friction_data.hpp"

#include <cmath>
#include <numbers>
#include <random>

namespace tpf::offline {

TcnSequence make_synthetic_friction_sequence(double seconds, double sample_rate_hz,
                                             std::uint64_t seed, double noise_std) {
  const Eigen::Index n = static_cast<Eigen::Index>(std::llround(seconds * sample_rate_hz));
  const double dt = 1.0 / sample_rate_hz;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 1.0);

  constexpr int kSines = 4;
  double amplitude[kSines], frequency[kSines], phase[kSines];
  for (int k = 0; k < kSines; ++k) {
    amplitude[k] = 0.05 + 0.15 * unit(rng);
    frequency[k] = 0.05 + 1.2 * unit(rng);
    phase[k] = 2.0 * std::numbers::pi * unit(rng);
  }

  constexpr double kFc = 0.5, kFs = 0.8, kVs = 0.05, kSigma0 = 200.0, kSigma1 = 0.5;
  TcnSequence s;
  s.inputs.resize(n, 4);
  s.residual.resize(n, 1);
  double q = 0.0, v_prev = 0.0, z = 0.0, gate = 0.0, gate_target = 1.0, next_switch = 0.0;
  const double gate_alpha = dt / 0.1;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double t = i * dt;
    if (t >= next_switch) {
      gate_target = unit(rng) < 0.7 ? 1.0 : 0.0;
      next_switch = t + 1.0 + 3.0 * unit(rng);
    }
    gate += gate_alpha * (gate_target - gate);
    double v = 0.0;
    for (int k = 0; k < kSines; ++k) {
      v += amplitude[k] * std::sin(2.0 * std::numbers::pi * frequency[k] * t + phase[k]);
    }
    v *= gate;
    if (std::abs(v) < 1e-4) v = 0.0;  // a resting joint
    q += v * dt;
    const double a = i == 0 ? 0.0 : (v - v_prev) / dt;
    v_prev = v;

    const double stribeck = kFc + (kFs - kFc) * std::exp(-(v / kVs) * (v / kVs));
    const double z_new = (z + v * dt) / (1.0 + kSigma0 * std::abs(v) * dt / stribeck);
    const double z_dot = (z_new - z) / dt;
    z = z_new;
    const double static_estimate = std::abs(v) < 1e-3 ? kSigma0 * z : 0.0;
    s.inputs.row(i) << q, v, a, static_estimate;
    s.residual(i, 0) = kSigma0 * z + kSigma1 * z_dot - kFc * std::tanh(v / 0.02) +
                       0.03 * std::sin(6.0 * q) + noise_std * noise(rng);
  }
  return s;
}

}  // namespace tpf::offline
