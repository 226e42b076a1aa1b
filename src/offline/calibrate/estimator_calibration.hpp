// Calibration of an arm's estimator parameters on a contact-free log, once, offline: what the
// run-time loop loads from an estimator parameter file (tpf calibrate → <arm>.estimator.json).
#pragma once

#include "offline/log/log.hpp"
#include "offline/replay/replay_estimator.hpp"

namespace tpf::offline {

/// The estimator parameters of `setup`'s arm (its nominal model, pads and compensator; its
/// parameters are replaced) calibrated on the contact-free `log`, as `tpf evaluate` does:
///  1. sensor noise σ (estimate_sensor_noise) → static dead band, pad hysteresis levels and pad
///     force gain for `pad_gain_kpa_per_n` (estimator_parameters_from_noise);
///  2.–4. calibrate_with_compensator.
/// Throws tpf::Error naming the log when a joint never rests or never starts moving.
ReplayParameters calibrate_estimator(ReplaySetup setup, const Log& log,
                                     double pad_gain_kpa_per_n = 1.5);

/// The steps that run the estimator with its compensator over the contact-free `log`, on
/// setup.parameters in place (the noise-derived parameters already set):
///  2. the compensator's domain: the log's speed and acceleration envelopes (speed_envelope,
///     acceleration_envelope);
///  3. σ of the nominal and compensated residuals in the static-to-kinetic transitions
///     (calibrate_sigma): the moving dead bands 1.5·σ — returned;
///  4. persistence of the torque-only contact alarm: no false alarm anywhere on the log
///     (calibrate_torque_alarm).
TransitionSigma<double, Eigen::Dynamic> calibrate_with_compensator(ReplaySetup& setup,
                                                                   const Log& log);

}  // namespace tpf::offline
