// The run-time estimator's parameters (everything but the nominal model and the TCN weights).
#pragma once

#include <limits>

#include "tpf/common/types.hpp"
#include "tpf/estimation/contact_force.hpp"
#include "tpf/estimation/static_friction_tracker.hpp"
#include "tpf/skin/skin.hpp"

namespace tpf {

/// Parameters of Estimator. Torques (σ's, dead bands) in N·m.
template <typename S, int N>
struct EstimatorParameters {
  S sample_period_s = S(0.0025);  ///< nominal period (400 Hz)
  S max_gap_factor = S(1.5);      ///< a step > factor·period is flagged as a gap
  S position_margin_rad = S(0.05);
  S acceleration_cutoff_hz = S(20);  ///< filtered derivative of q̇ when q̈ is not given
  S acceleration_damping = S(0.8);
  /// A reading repeated exactly for more samples than this is flagged frozen (joints) or stuck
  /// (pads); 200 = 0.5 s at 400 Hz. 0 disables (e.g. for noise-free simulated data).
  int frozen_limit_samples = 200;
  /// A pad pressure repeated exactly for more than this many samples is stuck (40 = 0.1 s at
  /// 400 Hz): a live pad's noise (≈ 3 ADC steps) repeats 40 times with probability < 1e-30, and
  /// the sooner a stuck pad is found the shorter the phantom contact it causes. Readings on the
  /// sensor's rails (0, skin.full_scale_kpa) do not count: saturation is a hard push. 0 disables.
  int stuck_pad_limit_samples = 40;

  StaticFrictionSettings<S> static_friction;
  SkinSettings<S> skin;
  ContactForceSettings<S> wrench;

  /// σ of the estimation error in the static-to-kinetic transition on contact-free data [N·m],
  /// from calibrate_transition_sigma: the proprioceptive (nominal) and fused (with TCN)
  /// estimators' dead bands are dead_band_factor·σ.
  JointVector<S, N> nominal_sigma = JointVector<S, N>::Zero();
  JointVector<S, N> fused_sigma = JointVector<S, N>::Zero();
  S dead_band_factor = S(1.5);
  /// The compensator's domain [rad/s]: the speeds its training data and the calibration of
  /// fused_sigma and torque_alarm_samples covered (e.g. max |q̇_j| of the contact-free
  /// calibration log, speed_envelope). On a joint moving faster the network extrapolates, so its
  /// Fused estimate falls back to the nominal residual τ_res with the nominal band
  /// dead_band_factor·nominal_sigma (kStatusOutsideCompensatorDomain). +inf: no limit.
  JointVector<S, N> compensator_speed_limit =
      JointVector<S, N>::Constant(std::numeric_limits<S>::infinity());
  /// The same for |q̈_j| [rad/s²] (the acceleration the compensator is given; e.g. the
  /// calibration log's max, acceleration_envelope). A joint stopped hard (a joint limit, an
  /// impact) drives the network far outside what it was trained on. +inf: no limit.
  JointVector<S, N> compensator_acceleration_limit =
      JointVector<S, N>::Constant(std::numeric_limits<S>::infinity());
  /// The held-out gate: a joint's network is used only where its weight file's held-out gain
  /// (1 − RMSE with / without it, per regime, written by `tpf train`) is at least this in every
  /// regime scored; elsewhere the joint runs on the nominal residual (kStatusCompensatorGated).
  /// 0: never worse than the nominal model on data the network was not trained on.
  S compensator_min_held_out_gain = S(0);
  /// The torque-only contact alarm (EstimatorOutput::contact without a pad) needs the combined
  /// external torque outside its dead band on some joint for this many consecutive cycles
  /// (PersistenceTest): a contact-free arm's outliers (break-away transitions) are short, a push
  /// is not. Chosen on a contact-free calibration log for a false-alarm rate
  /// (persistence_for_false_alarm_rate); 1 = every single exceedance alarms.
  int torque_alarm_samples = 1;
  /// Half-width of the static model-free estimate's dead band [N·m]: a few times the
  /// effort noise, e.g. 3·σ_noise·√(1 + 1/n_window) (see static_dead_band_from_noise).
  JointVector<S, N> static_dead_band = JointVector<S, N>::Zero();
};

/// Static dead band from the effort noise σ [N·m] (e.g. 6 mA current noise with 1 mA steps
/// → σ ≈ √(6² + 1/12) mA, times K_t/1000): Δτ_res = τ_res − mean of n samples has std σ·√(1 + 1/n),
/// and the band is k times that (k = 3).
template <typename S, int N>
JointVector<S, N> static_dead_band_from_noise(const JointVector<S, N>& noise, int window_samples,
                                              S k = S(3)) {
  using std::sqrt;
  return noise * (k * sqrt(S(1) + S(1) / S(window_samples > 0 ? window_samples : 1)));
}

}  // namespace tpf
