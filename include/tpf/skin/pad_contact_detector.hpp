// Contact detection on one pad: drift-compensated filtered pressure, a threshold with hysteresis,
// and the onset time of each contact.
#pragma once

#include <cmath>

#include "tpf/skin/pad_low_pass.hpp"

namespace tpf {

/// Settings of PadContactDetector. Pressures in kPa, times in s.
template <typename S>
struct PadDetectorSettings {
  S cutoff_hz = S(40);              ///< low-pass cut-off of the pressure
  S on_level_kpa = S(0.2);          ///< contact starts when p_f − offset rises above this
  S off_level_kpa = S(0.1);         ///< … and ends when it falls below this (< on level)
  S offset_time_constant_s = S(2);  ///< drift tracking of the no-contact offset (0: none)
};

/// Hysteresis levels from the raw pressure noise σ [kPa] at sample period h: the filtered noise is
/// σ_f = σ·√(α/(2−α)) with α = 1 − exp(−2π f_c h); on = k_on·σ_f, off = k_off·σ_f, each at least
/// one ADC step `resolution_kpa` above zero (on ≥ 2 steps). k_on = 8, k_off = 4 keep the false
/// on-rate of Gaussian noise below 1e-15 per sample and never chatter on noise.
template <typename S>
PadDetectorSettings<S> detector_settings_from_noise(S noise_kpa, S period_s,
                                                    S resolution_kpa = S(0), S cutoff_hz = S(40),
                                                    S k_on = S(8), S k_off = S(4)) {
  using std::max;
  PadDetectorSettings<S> s;
  s.cutoff_hz = cutoff_hz;
  const S filtered = noise_kpa * low_pass_noise_gain(low_pass_coefficient(cutoff_hz, period_s));
  s.off_level_kpa = max(k_off * filtered, resolution_kpa);
  s.on_level_kpa = max(k_on * filtered, S(2) * max(resolution_kpa, s.off_level_kpa / S(2)));
  if (s.on_level_kpa <= s.off_level_kpa) s.on_level_kpa = S(2) * s.off_level_kpa;
  return s;
}

/// What a detector's update needs from the sample period h besides the readings: the low-pass
/// coefficient α(h) and the offset tracker's gain 1 − exp(−h/τ_offset) (0 without tracking). Pads
/// with the same settings share them: the skin computes them once per sample, not once per pad.
template <typename S>
struct PadStepFactors {
  S filter_alpha = S(0);
  S offset_gain = S(0);

  static PadStepFactors at(const PadDetectorSettings<S>& settings, S h) noexcept {
    using std::exp;
    const S tau = settings.offset_time_constant_s;
    return {low_pass_coefficient(settings.cutoff_hz, h), tau > S(0) ? S(1) - exp(-h / tau) : S(0)};
  }
};

/// One pad's contact state. With p_f the low-passed pressure and o the offset (tracked by a slow
/// low-pass of p_f while no contact, frozen during contact), the load is u = p_f − o and
///   off → on when u > on_level,   on → off when u < off_level.
/// The onset time is the time of the last sample with u ≤ off_level before the rise, i.e. when the
/// pressure left the noise band, not when it crossed the on level (the force began before that).
/// Allocation-free; the caller guarantees finite pressures.
template <typename S>
class PadContactDetector {
 public:
  PadContactDetector() noexcept : PadContactDetector(PadDetectorSettings<S>{}) {}
  explicit PadContactDetector(const PadDetectorSettings<S>& settings) noexcept
      : settings_(settings), filter_(settings.cutoff_hz) {}

  /// Starts from pressure p at time t, without contact, offset = p.
  void reset(S t, S p) noexcept {
    filter_.reset(p);
    offset_ = p;
    in_contact_ = false;
    onset_ = quiet_since_ = t;
    changed_ = false;
  }

  /// Advances by the pressure p [kPa] at time t, h = t − t_previous > 0. Returns in_contact().
  bool update(S t, S p, S h) noexcept { return update(t, p, PadStepFactors<S>::at(settings_, h)); }

  /// The same with the factors of this sample's h and these settings already computed.
  bool update(S t, S p, const PadStepFactors<S>& factors) noexcept {
    const S filtered = filter_.update_with_coefficient(p, factors.filter_alpha);
    const S load = filtered - offset_;
    const bool was = in_contact_;
    if (in_contact_) {
      in_contact_ = load >= settings_.off_level_kpa;
    } else if (load > settings_.on_level_kpa) {
      in_contact_ = true;
      onset_ = quiet_since_;
    }
    if (!in_contact_) {
      if (load <= settings_.off_level_kpa) quiet_since_ = t;
      if (settings_.offset_time_constant_s > S(0) && load <= settings_.off_level_kpa)
        offset_ += factors.offset_gain * load;
    }
    changed_ = was != in_contact_;
    return in_contact_;
  }

  bool in_contact() const noexcept { return in_contact_; }
  /// True when the last update switched the state (onset or release).
  bool changed() const noexcept { return changed_; }
  /// Time the current (or last) contact began [s].
  S onset_time() const noexcept { return onset_; }
  /// Low-passed pressure minus the no-contact offset [kPa].
  S load_kpa() const noexcept { return filter_.value() - offset_; }
  S filtered_kpa() const noexcept { return filter_.value(); }
  S offset_kpa() const noexcept { return offset_; }
  const PadDetectorSettings<S>& settings() const noexcept { return settings_; }

 private:
  PadDetectorSettings<S> settings_;
  PadLowPass<S> filter_;
  S offset_ = S(0);
  S onset_ = S(0);
  S quiet_since_ = S(0);
  bool in_contact_ = false;
  bool changed_ = false;
};

}  // namespace tpf
