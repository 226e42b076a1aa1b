// Static-friction tracking: the frozen baseline τ̂_fric,s of the model-free static estimate, and
// the same quantity as the TCN's fourth input. The offline trainer runs exactly this class.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>

#include "tpf/common/types.hpp"
#include "tpf/estimation/contact_state.hpp"

namespace tpf {

/// What to do with the baseline of a joint that stops while a pad is in contact.
enum class StopPolicy : std::uint8_t {
  /// Re-baseline: τ̂_fric,s = τ_res(t_stop) − r̂_ext(t_stop⁻), i.e. hold the last external estimate
  /// of the moving estimator and let the static estimate follow Δτ_res from there.
  HoldLastEstimate,
  /// The original work: keep whatever baseline the joint had before it moved (stale).
  KeepStale,
};

/// Settings of StaticFrictionTracker (times in s, velocity in rad/s).
template <typename S>
struct StaticFrictionSettings {
  /// |q̇_j| below this is static (with a coupled transmission: |(C·q̇)_m| of every motor m
  /// acting on joint j, StaticFrictionTracker::set_coupling). The PH54 reports velocity in
  /// 0.01 rev/min = 1.047e-3 rad/s steps, so any threshold in (0, 1.047e-3) means "the reported
  /// velocity is exactly zero"; the original's 1e-4 works as is. Raise it (e.g. 2.2e-3, two steps)
  /// only if the drive's velocity flickers by one step at rest.
  S static_velocity = S(1e-4);
  /// The onset baseline averages τ_res over [t_on − lead − window, t_on − lead).
  S baseline_lead_s = S(0.005);
  S baseline_window_s = S(0.0125);
  StopPolicy stop_policy = StopPolicy::HoldLastEstimate;
};

/// Per joint j, with r = τ_res = τ_meas − τ_dyn − τ_fric(nominal) in N·m
/// and static_j = |q̇_j| < v_s — with a coupled transmission (set_coupling, C motors × joints:
/// motor m turns with (C·q̇)_m and its friction acts on joint j through C(m, j)) static_j means
/// also every motor m with C(m, j) ≠ 0 is at rest, |(C·q̇)_m| < v_s: a still joint that a moving
/// motor acts on feels that motor's kinetic friction, so no baseline is held on it:
///  - moving joint: τ̂_fric,s = 0, no baseline;
///  - static, no pad in contact: the baseline tracks r (mean over the last baseline_window_s);
///  - static, a pad switches on at t_on: baseline frozen at the mean of r over the window that
///    ends baseline_lead_s before t_on (from a short history, so the force that the pad needed
///    time to detect is not in it); further pads keep the frozen value;
///  - joint stops while a pad is in contact: HoldLastEstimate sets baseline = r − r̂_ext with r̂_ext
///    the moving estimator's last external residual (KeepStale keeps the old baseline);
///  - contact ends: tracking resumes.
/// τ̂_fric,s = baseline on static joints, 0 on moving ones; the static estimate of the external
/// residual is Δr = r − baseline on static joints (model-free: only a noise dead band is needed).
///
/// Trainer use (contact-free logs), row by row in time order (the offline tools replay the
/// Estimator itself, which sets the model's coupling here):
///   tracker.reset();  // after set_coupling(model.coupling) where model.coupled
///   for each row: tracker.update(t, dq, residual, false, +inf, zero);  // residual = τ_res
///                 input = compensator_input(q, dq, ddq, tracker.friction_estimate(),
///                                           friction);  // friction: predict_effort's
/// Allocation-free, no exceptions, after construction (which sizes everything at Eigen::Dynamic).
/// History holds `History` samples (64 = 160 ms at 400 Hz).
template <typename S, int N, int History = 64>
class StaticFrictionTracker {
 public:
  using Vector = JointVector<S, N>;
  using Mask = std::uint32_t;  ///< bit j: joint j
  static_assert(N <= 32, "joint masks are 32 bits wide");

  /// A tracker of `joints` joints (N where N is fixed; 0 … 32 at Eigen::Dynamic, where the
  /// default is none).
  explicit StaticFrictionTracker(const StaticFrictionSettings<S>& settings = {},
                                 int joints = N) noexcept(N != Eigen::Dynamic)
      : settings_(settings) {
    if constexpr (N == Eigen::Dynamic) {
      joints = std::max(joints, 0);
      assert(joints <= 32);
      baseline_.resize(joints);
      friction_.resize(joints);
      external_.resize(joints);
      for (Entry& e : history_)
        e.residual = Vector::Zero(joints);
    }
    (void)joints;
    reset();
  }

  /// The joint count (N where N is fixed).
  int joint_count() const noexcept {
    if constexpr (N == Eigen::Dynamic)
      return static_cast<int>(baseline_.size());
    else
      return N;
  }

  /// Start-up (allocates at Eigen::Dynamic): the transmission's coupling C (motors × joints,
  /// Model::coupling; joint_count() × joint_count()). From now on joint j is static only when it
  /// is still and every motor m with C(m, j) ≠ 0 has |(C·q̇)_m| < static_velocity. The identity
  /// gives the same masks and outputs as no coupling (the Estimator sets C only where
  /// Model::coupled, so an uncoupled arm keeps the per-joint test without the motor loop).
  void set_coupling(const JointMatrix<S, N>& coupling) noexcept(N != Eigen::Dynamic) {
    const int n = joint_count();
    assert(coupling.rows() == n && coupling.cols() == n);
    coupling_ = coupling;
    motors_on_.fill(0);
    joints_of_.fill(0);
    for (int j = 0; j < n; ++j)
      for (int m = 0; m < n; ++m)
        if (coupling(m, j) != S(0)) {
          motors_on_[static_cast<std::size_t>(j)] |= Mask(1) << m;
          joints_of_[static_cast<std::size_t>(m)] |= Mask(1) << j;
        }
    coupled_ = true;
  }
  /// Back to the per-joint test |q̇_j| < static_velocity.
  void clear_coupling() noexcept { coupled_ = false; }
  bool coupled() const noexcept { return coupled_; }

  /// Forgets everything: no history, every joint moving, no baseline.
  void reset() noexcept {
    count_ = 0;
    head_ = 0;
    static_ = 0;
    frozen_ = 0;
    has_baseline_ = 0;
    stale_ = 0;
    from_onset_ = 0;
    baseline_.setZero();
    friction_.setZero();
    external_.setZero();
    state_ = ContactState::Dynamic;
  }

  /// One cycle. t [s], q̇ [rad/s] (joint velocities; the motors' are C·q̇ where coupled),
  /// r = τ_res [N·m], `contact`: a pad is in contact,
  /// `new_onset`: the earliest onset time [s] of pads that switched on at this cycle (+inf if
  /// none), `held_external`: the moving estimator's last external residual r̂_ext [N·m],
  /// used by HoldLastEstimate when a joint stops in contact).
  void update(S t, const Vector& dq, const Vector& residual, bool contact, S new_onset,
              const Vector& held_external) noexcept {
    using std::abs;
    const int n = joint_count();
    Mask now_static = 0;
    for (int j = 0; j < n; ++j)
      if (abs(dq[j]) < settings_.static_velocity) now_static |= Mask(1) << j;
    if (coupled_) now_static &= static_joints_of_motors(dq);
    push(t, residual, now_static);

    const bool onset = std::isfinite(new_onset);
    for (int j = 0; j < n; ++j) {
      const Mask bit = Mask(1) << j;
      if (!(now_static & bit)) {
        frozen_ &= ~bit;
        from_onset_ &= ~bit;
        has_baseline_ &= ~bit;
        continue;
      }
      const bool stopped = !(static_ & bit);
      if (stopped && contact) {
        if (settings_.stop_policy == StopPolicy::HoldLastEstimate || !(stale_ & bit)) {
          baseline_[j] = residual[j] - held_external[j];
          stale_ |= bit;
        }
        frozen_ |= bit;
        from_onset_ &= ~bit;
      } else if (contact && !(frozen_ & bit)) {
        // A first onset (or contact already present when the joint was last re-tracked).
        const S end = (onset ? new_onset : t) - settings_.baseline_lead_s;
        baseline_[j] = window_mean(j, end - settings_.baseline_window_s, end, baseline_[j]);
        frozen_ |= bit;
        stale_ |= bit;
        from_onset_ |= bit;
      } else if (!contact) {
        frozen_ &= ~bit;
        from_onset_ &= ~bit;
        baseline_[j] = window_mean(j, t - settings_.baseline_window_s, t + S(1), residual[j]);
        stale_ |= bit;
      }
      has_baseline_ |= bit;
    }
    static_ = now_static;

    const Mask all = n >= 32 ? ~Mask(0) : (Mask(1) << n) - 1;
    state_ = static_ != all ? ContactState::Dynamic
                            : (contact ? ContactState::StaticContact : ContactState::StaticFree);
    for (int j = 0; j < n; ++j) {
      const bool ok = has_baseline_ & (Mask(1) << j);
      friction_[j] = ok ? baseline_[j] : S(0);
      external_[j] = ok ? residual[j] - baseline_[j] : S(0);
    }
  }

  /// Re-takes the baseline of every joint frozen at a tactile onset from the window before
  /// `onset` (the earliest onset of the contacts still believed), for when the pad whose onset
  /// froze it turns out to be stuck: baseline_j = mean of r_j over [onset − lead − window,
  /// onset − lead) of its static stretch; unchanged where the history does not reach back that far
  /// (then the remaining contact began first and froze the baseline itself). The outputs follow at
  /// the next update.
  void refreeze(S onset) noexcept {
    const S end = onset - settings_.baseline_lead_s;
    for (int j = 0; j < joint_count(); ++j)
      if (frozen_ & from_onset_ & (Mask(1) << j))
        baseline_[j] = window_mean(j, end - settings_.baseline_window_s, end, baseline_[j]);
  }

  ContactState state() const noexcept { return state_; }
  /// τ̂_fric,s: the baseline on static joints, 0 on moving ones (the TCN input) [N·m].
  const Vector& friction_estimate() const noexcept { return friction_; }
  /// Δr = r − τ̂_fric,s on static joints (0 on moving ones): the model-free external residual.
  const Vector& static_external() const noexcept { return external_; }
  /// Bit j set: joint j static with a baseline, i.e. static_external()[j] is an estimate.
  Mask valid_mask() const noexcept { return has_baseline_; }
  /// Bit j set: joint j's baseline is frozen (contact present).
  Mask frozen_mask() const noexcept { return frozen_; }
  /// Bit j set: joint j's frozen baseline was taken before a tactile onset (not at a stop).
  Mask onset_mask() const noexcept { return from_onset_; }
  bool is_static(int j) const noexcept { return static_ & (Mask(1) << j); }
  const StaticFrictionSettings<S>& settings() const noexcept { return settings_; }

 private:
  struct Entry {
    S t;
    Vector residual;
    Mask is_static;
  };

  /// With the coupling: bit j set when every motor acting on joint j has |(C·q̇)_m| < v_s. The
  /// rate sums over C(m, j) ≠ 0 only, in joint order (the identity gives q̇_m itself, NaN too; a
  /// non-finite rate counts as moving, as a non-finite |q̇_j| does without coupling).
  Mask static_joints_of_motors(const Vector& dq) const noexcept {
    using std::abs;
    const int n = joint_count();
    Mask moving_motors = 0;
    for (int m = 0; m < n; ++m) {
      S rate = S(0);
      for (Mask b = joints_of_[static_cast<std::size_t>(m)]; b != 0; b &= b - 1) {
        const int j = std::countr_zero(b);
        rate += coupling_(m, j) * dq[j];
      }
      if (!(abs(rate) < settings_.static_velocity)) moving_motors |= Mask(1) << m;
    }
    Mask still = 0;
    for (int j = 0; j < n; ++j)
      if (!(motors_on_[static_cast<std::size_t>(j)] & moving_motors)) still |= Mask(1) << j;
    return still;
  }

  void push(S t, const Vector& r, Mask s) noexcept {
    Entry& e = history_[head_];  // in place: at Eigen::Dynamic its residual keeps its storage
    e.t = t;
    e.residual = r;
    e.is_static = s;
    head_ = head_ + 1 == History ? 0 : head_ + 1;
    if (count_ < History) ++count_;
  }

  /// Mean of joint j's residual over the history samples with t ∈ [from, to) of its current
  /// static stretch (samples from before its last motion belong to another friction state);
  /// `fallback` when there is none.
  S window_mean(int j, S from, S to, S fallback) const noexcept {
    S sum = S(0);
    int n = 0;
    for (int i = 0; i < count_; ++i) {
      const Entry& e = history_[(head_ - 1 - i + 2 * History) % History];
      if (e.t < from || !(e.is_static & (Mask(1) << j))) break;
      if (e.t < to) {
        sum += e.residual[j];
        ++n;
      }
    }
    return n > 0 ? sum / S(n) : fallback;
  }

  StaticFrictionSettings<S> settings_;
  std::array<Entry, History> history_{};
  int count_ = 0;
  int head_ = 0;
  Mask static_ = 0;  ///< static at the last update
  Mask frozen_ = 0;
  Mask has_baseline_ = 0;
  Mask stale_ = 0;        ///< a baseline value exists (for KeepStale)
  Mask from_onset_ = 0;   ///< frozen at a tactile onset
  bool coupled_ = false;  ///< set_coupling was called: static per motor
  JointMatrix<S, N> coupling_ = zero_or_empty<JointMatrix<S, N>>();
  std::array<Mask, 32> motors_on_{};  ///< per joint j: bit m set where C(m, j) ≠ 0
  std::array<Mask, 32> joints_of_{};  ///< per motor m: bit j set where C(m, j) ≠ 0
  Vector baseline_ = zero_or_empty<Vector>();
  Vector friction_ = zero_or_empty<Vector>();
  Vector external_ = zero_or_empty<Vector>();
  ContactState state_ = ContactState::Dynamic;
};

}  // namespace tpf
