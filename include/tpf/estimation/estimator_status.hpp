// What the estimator could not do in a cycle: a bitfield, never an exception.
#pragma once

#include <cstdint>

namespace tpf {

/// Bits of EstimatorOutput::status. 0 = everything computed from fresh, finite data.
enum EstimatorStatus : std::uint32_t {
  kStatusOk = 0,
  /// t, q, q̇ or the effort held NaN/inf: the sample was skipped, the previous good state and
  /// outputs are kept; the next finite sample is processed normally.
  kStatusNonFiniteInput = 1u << 0,
  /// t did not advance (t ≤ previous t, or the first sample is not finite): sample skipped.
  kStatusStaleTime = 1u << 1,
  /// t − t_prev exceeded max_gap_factor × the sample period (dropped cycles): processed with the
  /// real period, but filters and the TCN history saw a gap.
  kStatusTimeGap = 1u << 2,
  /// A joint position is outside [lower − margin, upper + margin] of the model.
  kStatusPositionOutOfRange = 1u << 3,
  /// A pad pressure was NaN/inf: that pad kept its previous state.
  kStatusPadDataInvalid = 1u << 4,
  /// A pad is in contact but the contact force is not observable (see ContactForce::valid).
  kStatusWrenchUnobservable = 1u << 5,
  /// The given q̈ was not finite: the filtered derivative of q̇ was used instead.
  kStatusAccelerationEstimated = 1u << 6,
  /// A joint's q, q̇ and effort have all repeated bit for bit for more than frozen_limit_samples
  /// samples while t advanced: a frozen sensor or a stalled bus. Processed as given; distrust it.
  kStatusFrozenInput = 1u << 7,
  /// A pad's pressure has repeated bit for bit for more than stuck_pad_limit_samples samples
  /// (stuck or saturated). Clears as soon as the reading changes; the pad stays ignored
  /// (kStatusPadIgnored) until its detector has released.
  kStatusPadStuck = 1u << 8,
  /// A pad is disbelieved (Skin::set_ignored): it was found stuck and has not yet been seen
  /// live and released since. Its contact reaches neither the state machine nor the wrench; a
  /// static-friction baseline its phantom onset froze is re-taken at the remaining contacts' onset.
  kStatusPadIgnored = 1u << 9,
  /// A joint is outside the compensator's domain (EstimatorParameters::compensator_speed_limit,
  /// compensator_acceleration_limit: what it was trained and calibrated on), now or within the
  /// network's input window: its Fused estimate is the nominal one.
  kStatusOutsideCompensatorDomain = 1u << 10,
  /// A joint's compensator is gated off (Estimator::compensated_joints): its network did not
  /// lower the nominal residual on held-out data by compensator_min_held_out_gain in every regime
  /// scored, so its Fused estimate is the nominal one, every cycle.
  kStatusCompensatorGated = 1u << 11,
};

/// Number of status bits (bits 0 … kEstimatorStatusBits − 1).
inline constexpr int kEstimatorStatusBits = 12;

/// Name of status bit b ("non-finite input (skipped)", …), for reports; "unknown" outside.
constexpr const char* estimator_status_name(int bit) noexcept {
  constexpr const char* names[kEstimatorStatusBits] = {"non-finite input (skipped)",
                                                       "stale time (skipped)",
                                                       "time gap",
                                                       "position out of range",
                                                       "pad data invalid",
                                                       "wrench unobservable",
                                                       "acceleration estimated",
                                                       "frozen input",
                                                       "pad stuck",
                                                       "pad ignored",
                                                       "outside compensator domain",
                                                       "compensator gated (held out)"};
  return bit >= 0 && bit < kEstimatorStatusBits ? names[bit] : "unknown";
}

}  // namespace tpf
