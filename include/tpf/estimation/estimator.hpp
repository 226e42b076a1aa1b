// The run-time estimator: one update per control cycle fuses the nominal model, the skin, the
// contact-aware state machine and the TCN into external joint torques and a contact force.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "tpf/common/all_finite.hpp"
#include "tpf/estimation/acceleration_filter.hpp"
#include "tpf/estimation/compensator.hpp"
#include "tpf/estimation/contact_force.hpp"
#include "tpf/estimation/dead_band.hpp"
#include "tpf/estimation/estimator_parameters.hpp"
#include "tpf/estimation/estimator_status.hpp"
#include "tpf/estimation/estimator_types.hpp"
#include "tpf/estimation/nominal_model.hpp"
#include "tpf/estimation/persistence_test.hpp"
#include "tpf/estimation/repeated_reading_detector.hpp"
#include "tpf/estimation/static_friction_tracker.hpp"
#include "tpf/kinematics/contact_frame.hpp"
#include "tpf/kinematics/point_jacobian.hpp"
#include "tpf/skin/skin.hpp"

namespace tpf {

/// External torque and contact force of an N-joint arm with P skin pads, per cycle:
///  1. q̈: the sample's, or the filtered derivative of q̇ (AccelerationFilter);
///  2. nominal model: τ_dyn, τ_fric = predict_effort(q, q̇, q̈) on the joint transforms alone
///     (the link poses are computed in step 7, up to the contacted pad's link, only with a
///     contact); τ_res = τ_meas − τ_dyn − τ_fric;
///  3. skin: filtered pressure, hysteresis, contact flags and onset times (Skin);
///  4. state machine and static-friction baseline τ̂_fric,s (StaticFrictionTracker);
///  5. compensator: τ_TCN = C(q, q̇, q̈, τ̂_fric,s, τ_fric) (compensator_input; τ_fric is step 2's);
///  6. two estimates (TorqueEstimator), each with its dead band, and the combined one (Fused
///     is the nominal residual on joints outside the compensator's speed or acceleration domain,
///     and for the network's input window after);
///  7. contact force at the most loaded pad (estimate_contact_force), contact frame z = normal;
///  8. contact: a pad, or the combined torque outside its band for a while (PersistenceTest).
/// `Compensator` is tpf::Tcn<S, 5N, H, L, K, N>, PerJointTcnCompensator or ZeroCompensator<S, N>
/// (none); a controller names it by its kind (compensator_types.hpp) and builds the estimator
/// with load_estimator. P = 0: an arm without skin (proprioception only). P = Eigen::Dynamic:
/// the pad count of the layout, for offline tools (the samples' pressure vectors then live on the
/// heap). With fixed N and P, update() allocates nothing, throws nothing and never blocks; what
/// it could not do is in the output's status bits. The object is large with a TCN inside: keep
/// it on the heap.
template <typename S, int N, int P, typename Compensator = ZeroCompensator<S, N>>
requires FrictionCompensator<Compensator, S, N>
class Estimator {
 public:
  using Vector = JointVector<S, N>;
  using Sample = EstimatorSample<S, N, P>;
  using Output = EstimatorOutput<S, N>;

  /// Start-up: takes its own copies of everything. Throws tpf::Error when the pad layout does not
  /// have P pads or names a link outside 1..N.
  Estimator(NominalModel<S, N> nominal, const std::vector<Pad>& pads,
            const EstimatorParameters<S, N>& parameters, Compensator compensator = {})
      : nominal_(std::move(nominal)),
        links_(nominal_links(nominal_)),
        data_(nominal_.model),
        parameters_(parameters),
        skin_(pads, parameters.skin, N),
        tracker_(parameters.static_friction),
        acceleration_(parameters.acceleration_cutoff_hz, parameters.acceleration_damping),
        frozen_joints_(parameters.frozen_limit_samples),
        stuck_pads_(parameters.stuck_pad_limit_samples),
        torque_alarm_(parameters.torque_alarm_samples),
        compensator_(std::move(compensator)) {
    update_sigmas();
  }

  /// Forgets the past: the next sample starts every filter, the state machine and the TCN.
  void reset() noexcept {
    started_ = false;
    output_ = Output{};
    tracker_.reset();
  }

  /// One cycle (see the class comment). Returns the outputs; on a skipped sample (non-finite or
  /// stale) the previous outputs with this cycle's status bits.
  const Output& update(const Sample& sample) noexcept {
    if (!finite(sample)) {
      output_.status = kStatusNonFiniteInput;
      return output_;
    }
    if (started_ && !(sample.t > output_.t)) {
      output_.status = kStatusStaleTime;
      return output_;
    }
    const bool first = !started_;
    const InputCheck input = check_input(sample);
    const Acceleration a = acceleration(sample, input.h);  // 1
    std::uint32_t status = input.status | a.status | range_status(sample);
    nominal_residual(sample, a.ddq);                                              // 2
    status |= update_skin(sample, input);                                         // 3
    update_state_machine(sample);                                                 // 4
    compensate(sample, a.ddq, first);                                             // 5
    const FusedEvidence fused = estimate_external_torque(sample, a.ddq, status);  // 6
    status |= estimate_wrench(fused);                                             // 7
    const bool torque_alarm = torque_alarm_.update(fused.outside_band);           // 8
    output_.contact = skin_.any_contact() || torque_alarm;
    output_.ddq = a.ddq;
    output_.t = sample.t;
    output_.status = status;
    return output_;
  }

  const Output& output() const noexcept { return output_; }
  const Skin<S, P>& skin() const noexcept { return skin_; }
  const StaticFrictionTracker<S, N>& tracker() const noexcept { return tracker_; }
  const NominalModel<S, N>& nominal() const noexcept { return nominal_; }
  const EstimatorParameters<S, N>& parameters() const noexcept { return parameters_; }
  /// Replaces the transition σ of the two model-based dead bands (after calibration).
  void set_transition_sigma(const Vector& nominal_sigma, const Vector& fused_sigma) noexcept {
    parameters_.nominal_sigma = nominal_sigma;
    parameters_.fused_sigma = fused_sigma;
    update_sigmas();
  }
  /// σ of the torque evidence the wrench weighs [N·m]: on a resting joint
  /// √((static band/3)² + τ_s²/3) — the noise plus the push the friction may hold unseen (up to
  /// the break-away level τ_s, taken as uniform); on a moving joint σ_fused (σ_nominal when there
  /// is no fused σ; the wrench settings' torque_noise_nm when neither is calibrated), σ_nominal
  /// on a joint outside the compensator's speed domain. A resting joint whose baseline was set
  /// when it stopped in contact weighs √(static² + moving²).
  const Vector& static_sigma() const noexcept { return static_sigma_; }
  const Vector& moving_sigma() const noexcept { return moving_sigma_; }
  Compensator& compensator() noexcept { return compensator_; }

  /// Start-up: the joints whose network the Fused estimate uses (bit j: joint j; default all),
  /// e.g. compensated_joints(weights, …) of the held-out gate. Elsewhere the Fused estimate is
  /// the nominal residual with the nominal band, flagged kStatusCompensatorGated every cycle.
  void set_compensated_joints(std::uint32_t mask) noexcept {
    compensated_joints_ = mask & kEveryJoint<N>;
  }
  std::uint32_t compensated_joints() const noexcept { return compensated_joints_; }

 private:
  /// What the sample's timing and readings say before any estimate: the step h, time gap, frozen
  /// joints, stuck pads.
  struct InputCheck {
    S h;
    std::uint32_t status = 0;
    std::uint32_t stuck_pads = 0;
  };
  InputCheck check_input(const Sample& sample) noexcept {
    InputCheck c{parameters_.sample_period_s};
    if (!started_) {
      start(sample);
      return c;
    }
    c.h = sample.t - output_.t;
    if (c.h > parameters_.max_gap_factor * parameters_.sample_period_s) c.status |= kStatusTimeGap;
    if (frozen_joints_.update(joint_reading(sample))) c.status |= kStatusFrozenInput;
    c.stuck_pads = stuck_pads_.update(off_rail(sample.pressure));
    if (c.stuck_pads) c.status |= kStatusPadStuck;
    return c;
  }

  /// 1. q̈: the sample's where it has a finite one, else the filtered derivative of q̇ (the filter
  /// always runs, so it is warm when q̈ goes missing).
  struct Acceleration {
    Vector ddq;
    std::uint32_t status = 0;
  };
  Acceleration acceleration(const Sample& sample, S h) noexcept {
    const Vector& filtered = acceleration_.update(sample.dq, h);
    if (!sample.has_ddq) return {filtered};
    if (all_finite(sample.ddq)) return {sample.ddq};
    return {filtered, kStatusAccelerationEstimated};
  }

  std::uint32_t range_status(const Sample& sample) const noexcept {
    for (int j = 0; j < N; ++j)
      if (sample.q[j] < nominal_.model.lower[j] - parameters_.position_margin_rad ||
          sample.q[j] > nominal_.model.upper[j] + parameters_.position_margin_rad)
        return kStatusPositionOutOfRange;
    return 0;
  }

  /// 2. Nominal model on the joint transforms (data_.liMi at q; the world poses wait for step 7):
  /// τ_res = τ_meas − τ_dyn − τ_fric.
  void nominal_residual(const Sample& sample, const Vector& ddq) noexcept {
    Output& out = output_;
    joint_transforms(nominal_.model, data_, sample.q);
    predict_effort_at_pose(nominal_, links_, data_, sample.q, sample.dq, ddq, out.effort_rigid,
                           out.effort_friction);
    out.residual = sample.effort - out.effort_rigid - out.effort_friction;
  }

  /// 3. Skin. A stuck pad is disbelieved until it reads live again and its detector has
  /// released, so its phantom contact reaches neither the state machine nor the wrench.
  std::uint32_t update_skin(const Sample& sample, const InputCheck& input) noexcept {
    std::uint32_t status = 0;
    if (skin_.update(sample.t, input.h, sample.pressure) > 0) status |= kStatusPadDataInvalid;
    const std::uint32_t stuck = input.stuck_pads;
    const std::uint32_t newly_ignored = stuck & ~skin_.ignored();
    std::uint32_t ignored = skin_.ignored() | stuck;
    for (int k = 0; k < skin_.count(); ++k)
      if (!(stuck & (1u << k)) && !skin_.detector(k).in_contact()) ignored &= ~(1u << k);
    skin_.set_ignored(ignored);
    if (ignored) status |= kStatusPadIgnored;
    // A baseline frozen at the stuck pad's onset is re-taken at the remaining contacts' onset
    // (without remaining contact the tracker simply resumes tracking).
    if (newly_ignored && skin_.any_contact()) tracker_.refreeze(skin_.earliest_onset());
    return status;
  }

  /// 4. State machine, holding the last combined estimate for joints that stop in contact.
  void update_state_machine(const Sample& sample) noexcept {
    tracker_.update(sample.t, sample.dq, output_.residual, skin_.any_contact(),
                    skin_.earliest_new_onset(), held_residual_);
    output_.state = tracker_.state();
    output_.static_friction = tracker_.friction_estimate();
  }

  /// 5. Compensator, prewarmed on the first sample with its steady input (q̈ = 0, no baseline).
  void compensate(const Sample& sample, const Vector& ddq, bool first) noexcept {
    Output& out = output_;
    if (first)
      compensator_.reset(compensator_input<S, N>(sample.q, sample.dq, Vector::Zero().eval(),
                                                 Vector::Zero().eval(), out.effort_friction));
    out.compensation = compensator_.step(compensator_input<S, N>(
        sample.q, sample.dq, ddq, out.static_friction, out.effort_friction));
  }

  /// The fused torque evidence of one cycle, before its dead band, and its σ per joint.
  struct FusedEvidence {
    Vector residual;  ///< τ_res − τ_TCN, or τ_res outside the compensator's domain
    Vector sigma;
    bool outside_band = false;  ///< the combined estimate is outside its dead band somewhere
  };

  /// 6. External torque two ways and combined: StaticModelFree on resting joints, Fused
  /// elsewhere (the nominal residual and band on joints outside the compensator's domain).
  FusedEvidence estimate_external_torque(const Sample& sample, const Vector& ddq,
                                         std::uint32_t& status) noexcept {
    Output& out = output_;
    constexpr std::uint32_t all = kEveryJoint<N>;
    set_estimate(TorqueEstimator::StaticModelFree,
                 dead_band(tracker_.static_external(), parameters_.static_dead_band),
                 tracker_.valid_mask());
    FusedEvidence fused{out.residual - out.compensation, moving_sigma_};
    Vector fused_band = parameters_.dead_band_factor * parameters_.fused_sigma;
    for (int j = 0; j < N; ++j) {
      const bool outside = outside_compensator_domain(j, sample.dq[j], ddq[j]);
      const bool gated = !(compensated_joints_ & (1u << j));
      if (!outside && !gated) continue;
      fused.residual[j] = out.residual[j];
      fused_band[j] = parameters_.dead_band_factor * parameters_.nominal_sigma[j];
      fused.sigma[j] = nominal_moving_sigma_[j];
      status |=
          (outside ? kStatusOutsideCompensatorDomain : 0u) | (gated ? kStatusCompensatorGated : 0u);
    }
    set_estimate(TorqueEstimator::Fused, dead_band(fused.residual, fused_band), all);
    const ExternalTorque<S, N>& fixed = out.estimate(TorqueEstimator::StaticModelFree);
    const ExternalTorque<S, N>& moving = out.estimate(TorqueEstimator::Fused);
    // Element by element: the values were just stored that way (a vector load of them would wait).
    for (int j = 0; j < N; ++j) {
      const bool use_static = fixed.valid & (1u << j);
      const S residual = use_static ? fixed.residual[j] : moving.residual[j];
      out.external.residual[j] = residual;
      out.external.torque[j] = use_static ? fixed.torque[j] : moving.torque[j];
      held_residual_[j] = residual;  // what a joint stopping next cycle holds
      fused.outside_band = fused.outside_band || residual != S(0);
    }
    out.external.valid = all;
    return fused;
  }

  /// Whether joint j's compensator input is outside the domain now or was within the network's
  /// input window: its output depends on the whole window.
  bool outside_compensator_domain(int j, S dq, S ddq) noexcept {
    using std::abs;
    if (abs(dq) > parameters_.compensator_speed_limit[j] ||
        abs(ddq) > parameters_.compensator_acceleration_limit[j])
      outside_domain_[j] = compensator_memory_of(compensator_);
    else if (outside_domain_[j] > 0)
      --outside_domain_[j];
    return outside_domain_[j] > 0;
  }

  /// 7. Contact force at the most loaded pad: the torque evidence (before any dead band: the
  /// static Δτ_res on resting joints, the fused residual on moving ones) weighted by its σ, with
  /// the pad's reading as the prior. One pad touched: the fused external torque is that of the
  /// fused force, τ = J_vᵀ f̂ (both senses, consistent with a force at the pad); several pads:
  /// four torques cannot separate the forces, so the torque estimate stands.
  std::uint32_t estimate_wrench(const FusedEvidence& fused) noexcept {
    Output& out = output_;
    out.wrench = ContactForce<S>{};
    const int pad = skin_.most_loaded();
    if (pad < 0) return 0;
    const PadGeometry<S>& g = skin_.geometry(pad);
    link_poses(nominal_.model, data_, g.link);  // on step 2's joint transforms
    const Vector3<S> point = pad_point_in_world(data_, g);
    point_jacobian(nominal_.model, data_, g.link, point, jacobian_);
    // A joint that stopped in contact took its baseline from the moving estimate it held
    // (HoldLastEstimate), so its evidence also carries that estimate's error: σ² adds up.
    const ExternalTorque<S, N>& fixed = out.estimate(TorqueEstimator::StaticModelFree);
    const std::uint32_t held = tracker_.frozen_mask() & ~tracker_.onset_mask();
    Vector evidence, sigma;
    for (int j = 0; j < N; ++j) {
      const bool at_rest = fixed.valid & (1u << j);
      const S r = at_rest ? tracker_.static_external()[j] : fused.residual[j];
      evidence[j] = -r;
      const S s = !at_rest             ? fused.sigma[j]
                  : (held & (1u << j)) ? held_sigma_[j]
                                       : static_sigma_[j];
      sigma[j] = s;
    }
    out.wrench = estimate_contact_force(jacobian_, pad_contact_frame_in_world(data_, g), evidence,
                                        sigma, skin_.normal_force(pad), parameters_.wrench);
    out.wrench.pad = pad;
    out.wrench.point_world = point;
    if (skin_.contact_count() == 1 && all_finite(out.wrench.force_world)) {
      out.external.torque = jacobian_.template topRows<3>().transpose() * out.wrench.force_world;
      out.external.residual = -out.external.torque;
    }
    return out.wrench.valid ? 0u : std::uint32_t(kStatusWrenchUnobservable);
  }

  /// Finite t, q, q̇ and effort (and, with a start-up pad count, one pressure per pad).
  bool finite(const Sample& s) const noexcept {
    if constexpr (P == Eigen::Dynamic)
      if (s.pressure.size() != skin_.count()) return false;
    return std::isfinite(s.t) && all_finite(s.q, s.dq, s.effort);
  }

  /// The pad readings for stuck detection: a reading on a rail (≤ 0 or ≥ full scale) is NaN, so
  /// it never counts as a repeat — a push that saturates the sensor is not a stuck pad.
  Eigen::Matrix<S, P, 1> off_rail(const Eigen::Matrix<S, P, 1>& p) const noexcept {
    Eigen::Matrix<S, P, 1> r = p;
    for (Eigen::Index k = 0; k < p.size(); ++k)
      if (!(p[k] > S(0) && p[k] < parameters_.skin.full_scale_kpa))
        r[k] = std::numeric_limits<S>::quiet_NaN();
    return r;
  }

  /// A joint's reading as one row: [q, q̇, effort].
  static Eigen::Matrix<S, N, 3> joint_reading(const Sample& s) noexcept {
    Eigen::Matrix<S, N, 3> r;
    r.col(0) = s.q;
    r.col(1) = s.dq;
    r.col(2) = s.effort;
    return r;
  }

  void update_sigmas() noexcept {
    const Vector floor = Vector::Constant(parameters_.wrench.torque_noise_nm);
    const Vector noise = parameters_.static_dead_band / S(3);
    static_sigma_ = (noise.cwiseAbs2() + nominal_.friction.static_friction.cwiseAbs2() / S(3))
                        .cwiseSqrt()
                        .cwiseMax(floor);
    for (int j = 0; j < N; ++j) {
      const S fused = parameters_.fused_sigma[j], nominal = parameters_.nominal_sigma[j];
      nominal_moving_sigma_[j] = nominal > S(0) ? nominal : floor[j];
      moving_sigma_[j] = fused > S(0) ? fused : nominal_moving_sigma_[j];
      held_sigma_[j] = std::hypot(static_sigma_[j], moving_sigma_[j]);
    }
  }

  void start(const Sample& sample) noexcept {
    started_ = true;
    frozen_joints_.reset(joint_reading(sample));
    stuck_pads_.reset(off_rail(sample.pressure));
    acceleration_.reset(sample.dq);
    Eigen::Matrix<S, P, 1> p = sample.pressure;
    for (Eigen::Index k = 0; k < p.size(); ++k)
      if (!std::isfinite(p[k])) p[k] = S(0);
    skin_.reset(sample.t, p);
    skin_.set_ignored(0);
    tracker_.reset();
    torque_alarm_.reset();
    held_residual_.setZero();
    outside_domain_.fill(0);
  }

  void set_estimate(TorqueEstimator which, const Vector& residual, std::uint32_t valid) noexcept {
    ExternalTorque<S, N>& e = output_.estimates[static_cast<int>(which)];
    for (int j = 0; j < N; ++j) {
      const bool ok = valid & (1u << j);
      e.residual[j] = ok ? residual[j] : S(0);
      e.torque[j] = -e.residual[j];
    }
    e.valid = valid;
  }

  NominalModel<S, N> nominal_;
  NominalLinks<S, N> links_;  ///< nominal_ in link form for the per-cycle dynamics
  Data<S, N> data_;
  EstimatorParameters<S, N> parameters_;
  Skin<S, P> skin_;
  StaticFrictionTracker<S, N> tracker_;
  AccelerationFilter<S, N> acceleration_;
  RepeatedReadingDetector<S, N, 3> frozen_joints_;
  RepeatedReadingDetector<S, P> stuck_pads_;
  PersistenceTest torque_alarm_;
  Compensator compensator_;
  std::uint32_t compensated_joints_ = kEveryJoint<N>;
  Jacobian<S, N> jacobian_ = Jacobian<S, N>::Zero();
  Vector held_residual_ = Vector::Zero();  ///< last torque-only estimate (StopPolicy)
  /// Per joint: cycles until its compensator input window is back inside the domain.
  std::array<int, N> outside_domain_{};
  Vector static_sigma_ = Vector::Zero();
  Vector moving_sigma_ = Vector::Zero();
  Vector nominal_moving_sigma_ = Vector::Zero();  ///< σ_nominal (floor when uncalibrated)
  Vector held_sigma_ = Vector::Zero();  ///< √(static² + moving²): a baseline held at a stop
  Output output_;
  bool started_ = false;
};

}  // namespace tpf
