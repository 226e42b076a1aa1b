// Synthetic, friction-like training data (for tests and benchmarks; not simulated, not measured).
#pragma once

#include <cstdint>

#include "offline/compensator_training/tcn_trainer.hpp"

namespace tpf::offline {

/// One joint, `seconds` of samples at `sample_rate_hz`, deterministic by seed. SYNTHETIC data.
///
/// Motion: q̇(t) = g(t)·Σ_k A_k sin(2π f_k t + φ_k) with a smoothed random move/hold gate g, so
/// the joint also rests (stick); q integrates q̇, q̈ differentiates it.
/// Residual (what a Coulomb nominal model misses): a LuGre bristle state z,
///   ż = q̇ − σ₀|q̇|z/s(q̇),  s(q̇) = F_c + (F_s − F_c)·exp(−(q̇/v_s)²)   (implicit Euler step),
///   r = σ₀z + σ₁ż − F_c·tanh(q̇/0.02) + 0.03·sin(6q) + white noise of std `noise_std` [N·m],
/// F_c = 0.5, F_s = 0.8 N·m, v_s = 0.05 rad/s, σ₀ = 200 N·m/rad, σ₁ = 0.5 N·m·s/rad.
/// Inputs per row: [q, q̇, q̈, τ̂_fric,s] with τ̂_fric,s = σ₀z while |q̇| < 10⁻³ rad/s, else 0.
TcnSequence make_synthetic_friction_sequence(double seconds, double sample_rate_hz,
                                             std::uint64_t seed, double noise_std = 0.005);

}  // namespace tpf::offline
