// The proprioceptive-only baseline: what the motor currents and the nominal model alone say.
#pragma once

#include "tpf/estimation/dead_band.hpp"
#include "tpf/estimation/estimator_parameters.hpp"
#include "tpf/estimation/estimator_types.hpp"

namespace tpf {

/// The external torque of the nominal model alone, the baseline an evaluation compares the
/// estimator's answer with: the residual τ_res = τ_meas − τ_dyn − τ_fric of `out` through the
/// dead band dead_band_factor·σ_nominal, on every joint. Estimator::update does not compute it
/// (no controller needs it); an evaluation derives it from each cycle's output. Allocates at
/// Eigen::Dynamic.
template <typename S, int N>
ExternalTorque<S, N> proprioceptive_estimate(
    const EstimatorOutput<S, N>& out,
    const EstimatorParameters<S, N>& parameters) noexcept(N != Eigen::Dynamic) {
  ExternalTorque<S, N> e;
  e.residual = dead_band(out.residual,
                         JointVector<S, N>(parameters.dead_band_factor * parameters.nominal_sigma));
  e.torque = -e.residual;
  e.valid = every_joint_mask(static_cast<int>(out.residual.size()));
  return e;
}

}  // namespace tpf
