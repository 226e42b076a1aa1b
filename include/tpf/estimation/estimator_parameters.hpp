// The run-time estimator's parameters (everything but the nominal model and the TCN weights).
#pragma once

#include <limits>
#include <string>
#include <utility>

#include "tpf/common/types.hpp"
#include "tpf/estimation/contact_force.hpp"
#include "tpf/estimation/static_friction_tracker.hpp"
#include "tpf/skin/skin.hpp"

namespace tpf {

/// Parameters of Estimator. Torques (σ's, dead bands) in N·m. At Eigen::Dynamic the per-joint
/// vectors are empty until resize(n) gives them n joints' defaults.
template <typename S, int N>
struct EstimatorParameters {
  using Vector = JointVector<S, N>;

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
  Vector nominal_sigma = zero_or_empty<Vector>();
  Vector fused_sigma = zero_or_empty<Vector>();
  S dead_band_factor = S(1.5);
  /// The compensator's domain [rad/s]: the speeds its training data and the calibration of
  /// fused_sigma and torque_alarm_samples covered (e.g. max |q̇_j| of the contact-free
  /// calibration log, speed_envelope). On a joint moving faster the network extrapolates, so its
  /// Fused estimate falls back to the nominal residual τ_res with the nominal band
  /// dead_band_factor·nominal_sigma (kStatusOutsideCompensatorDomain). +inf: no limit.
  Vector compensator_speed_limit = unlimited();
  /// The same for |q̈_j| [rad/s²] (the acceleration the compensator is given; e.g. the
  /// calibration log's max, acceleration_envelope). A joint stopped hard (a joint limit, an
  /// impact) drives the network far outside what it was trained on. +inf: no limit.
  Vector compensator_acceleration_limit = unlimited();
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
  Vector static_dead_band = zero_or_empty<Vector>();

  /// The joint count of the per-joint vectors (N where N is fixed).
  int joint_count() const noexcept { return static_cast<int>(nominal_sigma.size()); }

  /// Throws tpf::Error when a per-joint vector does not hold n joints, naming it and both counts
  /// (start-up: parameters assembled by hand at Eigen::Dynamic).
  void check_joint_count(int n) const {
    const std::pair<const char*, const Vector*> vectors[] = {
        {"nominal_sigma", &nominal_sigma},
        {"fused_sigma", &fused_sigma},
        {"compensator_speed_limit", &compensator_speed_limit},
        {"compensator_acceleration_limit", &compensator_acceleration_limit},
        {"static_dead_band", &static_dead_band}};
    for (const auto& [name, v] : vectors)
      if (v->size() != n)
        throw Error(std::string("the estimator parameters' ") + name + " has " +
                    std::to_string(v->size()) + " joints, the model has " + std::to_string(n));
  }

  /// The defaults of every per-joint vector for n joints (n = N where N is fixed); the scalar
  /// settings are kept. Start-up code (allocates at Eigen::Dynamic).
  void resize(int n) {
    nominal_sigma = fused_sigma = static_dead_band = Vector::Zero(n);
    compensator_speed_limit = compensator_acceleration_limit =
        Vector::Constant(n, std::numeric_limits<S>::infinity());
  }

 private:
  /// +inf on every joint (no limit), or empty at Eigen::Dynamic.
  static Vector unlimited() {
    if constexpr (N == Eigen::Dynamic)
      return Vector();
    else
      return Vector::Constant(std::numeric_limits<S>::infinity());
  }
};

/// The same parameters with the joint count as type `To`: Eigen::Dynamic, or a fixed count that
/// must equal the parameters' (tpf::Error naming both otherwise). Start-up code.
template <int To, typename S, int From>
EstimatorParameters<S, To> joint_count_cast(const EstimatorParameters<S, From>& from) {
  require_joint_count<To>(from.joint_count(), "the estimator parameters");
  from.check_joint_count(from.joint_count());
  EstimatorParameters<S, To> to;
  to.sample_period_s = from.sample_period_s;
  to.max_gap_factor = from.max_gap_factor;
  to.position_margin_rad = from.position_margin_rad;
  to.acceleration_cutoff_hz = from.acceleration_cutoff_hz;
  to.acceleration_damping = from.acceleration_damping;
  to.frozen_limit_samples = from.frozen_limit_samples;
  to.stuck_pad_limit_samples = from.stuck_pad_limit_samples;
  to.static_friction = from.static_friction;
  to.skin = from.skin;
  to.wrench = from.wrench;
  to.nominal_sigma = from.nominal_sigma;
  to.fused_sigma = from.fused_sigma;
  to.dead_band_factor = from.dead_band_factor;
  to.compensator_speed_limit = from.compensator_speed_limit;
  to.compensator_acceleration_limit = from.compensator_acceleration_limit;
  to.compensator_min_held_out_gain = from.compensator_min_held_out_gain;
  to.torque_alarm_samples = from.torque_alarm_samples;
  to.static_dead_band = from.static_dead_band;
  return to;
}

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
