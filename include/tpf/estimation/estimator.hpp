// The run-time estimator: one update per control cycle fuses the nominal model, the skin, the
// contact-aware state machine and the TCN into external joint torques and a contact force.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "tpf/common/all_finite.hpp"
#include "tpf/common/error.hpp"
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
///  4. state machine and static-friction baseline τ̂_fric,s (StaticFrictionTracker); a joint is
///     at rest when every motor acting on it is: |(C·q̇)_m| < static_velocity for each m with
///     C(m, j) ≠ 0 (Model::coupling; |q̇_j| on an uncoupled arm), since a still joint that a
///     turning motor acts on feels that motor's kinetic friction, not a held one;
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
/// heap). N = Eigen::Dynamic: the joint count of the nominal model (1 … 32), for offline tools
/// that run one compiled copy for any arm; every member is sized at construction, a sample whose
/// vectors have another size is skipped as kStatusNonFiniteInput, and the compensator is
/// ZeroCompensator or PerJointTcnCompensator (the all-joints Tcn is compiled for a fixed N).
/// update() allocates nothing, throws nothing and never blocks; what it could not do is in the
/// output's status bits. With fixed N and P its scratch vectors live on its stack; with a size
/// chosen at start-up they are members, sized once at construction, so that update() allocates
/// nothing there either (tests/estimation/estimator_run_time_size_test.cpp counts Eigen's
/// mallocs). The object is large with a TCN inside: keep it on the heap.
template <typename S, int N, int P, typename Compensator = ZeroCompensator<S, N>>
requires FrictionCompensator<Compensator, S, N>
class Estimator {
 public:
  using Vector = JointVector<S, N>;
  using Sample = EstimatorSample<S, N, P>;
  using Output = EstimatorOutput<S, N>;

  /// Start-up: takes its own copies of everything and sizes every member for the nominal model's
  /// joint count. Throws tpf::Error when the pad layout does not have P pads or names a link
  /// outside 1..N, when a parameter vector has another joint count than the model, or (at
  /// Eigen::Dynamic) when the model has more than 32 joints (32-bit joint masks).
  Estimator(NominalModel<S, N> nominal, const std::vector<Pad>& pads,
            const EstimatorParameters<S, N>& parameters, Compensator compensator = {})
      : nominal_(at_most_32_joints(std::move(nominal))),
        links_(nominal_links(nominal_)),
        data_(nominal_.model),
        parameters_(parameters),
        skin_(pads, parameters.skin, nominal_.model.joint_count()),
        tracker_(parameters.static_friction, nominal_.model.joint_count()),
        acceleration_(parameters.acceleration_cutoff_hz, parameters.acceleration_damping,
                      nominal_.model.joint_count()),
        frozen_joints_(parameters.frozen_limit_samples, nominal_.model.joint_count()),
        stuck_pads_(parameters.stuck_pad_limit_samples, skin_.count()),
        torque_alarm_(parameters.torque_alarm_samples),
        compensator_(std::move(compensator)) {
    const int n = nominal_.model.joint_count();
    parameters_.check_joint_count(n);
    if (nominal_.model.coupled) tracker_.set_coupling(nominal_.model.coupling);  // rest per motor
    resize_compensator(compensator_, n);
    compensated_joints_ = every_joint_mask(n);
    jacobian_ = Jacobian<S, N>::Zero(6, n);
    held_residual_ = static_sigma_ = moving_sigma_ = nominal_moving_sigma_ = held_sigma_ =
        Vector::Zero(n);
    resize_storage(outside_domain_, static_cast<std::size_t>(n));
    std::fill(outside_domain_.begin(), outside_domain_.end(), 0);
    output_.resize(n);
    if constexpr (kRunTimeSize) scratch_.resize(n, skin_.count());
    update_sigmas();
  }

  /// Forgets the past: the next sample starts every filter, the state machine and the TCN.
  void reset() noexcept {
    started_ = false;
    output_.clear();
    tracker_.reset();
  }

  /// One cycle (see the class comment). Returns the outputs; on a skipped sample (non-finite or
  /// stale) the previous outputs with this cycle's status bits.
  const Output& update(const Sample& sample) noexcept {
    if constexpr (kRunTimeSize) {
      return update(sample, scratch_);
    } else {
      Scratch scratch;  // on the stack: fixed sizes
      return update(sample, scratch);
    }
  }

  const Output& output() const noexcept { return output_; }
  const Skin<S, P>& skin() const noexcept { return skin_; }
  const StaticFrictionTracker<S, N>& tracker() const noexcept { return tracker_; }
  const NominalModel<S, N>& nominal() const noexcept { return nominal_; }
  const EstimatorParameters<S, N>& parameters() const noexcept { return parameters_; }
  /// The joint count (N where N is fixed, else the nominal model's).
  int joint_count() const noexcept {
    if constexpr (N == Eigen::Dynamic)
      return nominal_.model.joint_count();
    else
      return N;
  }
  /// Replaces the transition σ of the two model-based dead bands (after calibration; vectors of
  /// the estimator's joint count).
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
    compensated_joints_ = mask & every_joint_mask(joint_count());
  }
  std::uint32_t compensated_joints() const noexcept { return compensated_joints_; }

 private:
  /// Sizes chosen at start-up (joints or pads): the per-cycle scratch is then a member, sized
  /// once; with both fixed it lives on update()'s stack.
  static constexpr bool kRunTimeSize = N == Eigen::Dynamic || P == Eigen::Dynamic;

  /// The fused torque evidence of one cycle, before its dead band, and its σ per joint.
  struct FusedEvidence {
    Vector residual;  ///< τ_res − τ_TCN, or τ_res outside the compensator's domain
    Vector sigma;
    Vector band;                ///< the dead band's half-width per joint
    bool outside_band = false;  ///< the combined estimate is outside its dead band somewhere
  };

  /// The vectors one cycle works in.
  struct Scratch {
    Eigen::Matrix<S, N, 3> joint_reading;  ///< per joint [q, q̇, effort] (frozen-input check)
    Eigen::Matrix<S, P, 1> pressure;       ///< pad readings off the rails, or the finite ones
    Vector effort;  ///< the nominal model's working vector (predict_effort_at_pose)
    CompensatorInput<S, N> compensator_input;
    FusedEvidence fused;
    Vector evidence;  ///< the wrench's torque evidence and its σ
    Vector evidence_sigma;
    ContactForceWorkspace<S, N> contact;

    void resize(int joints, int pads) {
      joint_reading.resize(joints, 3);
      pressure.resize(pads);
      compensator_input.resize(kCompensatorInputsPerJoint * joints);
      for (Vector* v :
           {&effort, &fused.residual, &fused.sigma, &fused.band, &evidence, &evidence_sigma})
        v->resize(joints);
      contact.resize(joints);
    }
  };
  struct NoScratch {};

  /// The nominal model, refused (tpf::Error) when it has more joints than the masks hold.
  static NominalModel<S, N> at_most_32_joints(NominalModel<S, N>&& nominal) {
    if constexpr (N == Eigen::Dynamic) {
      const int n = nominal.model.joint_count();
      if (n > 32)
        throw Error("the model '" + nominal.model.name + "' has " + std::to_string(n) +
                    " joints; the estimator takes at most 32 (32-bit joint masks)");
    }
    return std::move(nominal);
  }

  const Output& update(const Sample& sample, Scratch& scratch) noexcept {
    if (!finite(sample)) {
      output_.status = kStatusNonFiniteInput;
      return output_;
    }
    if (started_ && !(sample.t > output_.t)) {
      output_.status = kStatusStaleTime;
      return output_;
    }
    const bool first = !started_;
    const InputCheck input = check_input(sample, scratch);
    const Acceleration a = acceleration(sample, input.h);  // 1
    const Vector& ddq = *a.ddq;
    std::uint32_t status = input.status | a.status | range_status(sample);
    nominal_residual(sample, ddq, scratch);                                      // 2
    status |= update_skin(sample, input);                                        // 3
    update_state_machine(sample);                                                // 4
    compensate(sample, ddq, first, scratch);                                     // 5
    estimate_external_torque(sample, ddq, status, scratch.fused);                // 6
    status |= estimate_wrench(scratch);                                          // 7
    const bool torque_alarm = torque_alarm_.update(scratch.fused.outside_band);  // 8
    output_.contact = skin_.any_contact() || torque_alarm;
    output_.ddq = ddq;
    output_.t = sample.t;
    output_.status = status;
    return output_;
  }

  /// What the sample's timing and readings say before any estimate: the step h, time gap, frozen
  /// joints, stuck pads.
  struct InputCheck {
    S h;
    std::uint32_t status = 0;
    std::uint32_t stuck_pads = 0;
  };
  InputCheck check_input(const Sample& sample, Scratch& scratch) noexcept {
    InputCheck c{parameters_.sample_period_s};
    if (!started_) {
      start(sample, scratch);
      return c;
    }
    c.h = sample.t - output_.t;
    if (c.h > parameters_.max_gap_factor * parameters_.sample_period_s) c.status |= kStatusTimeGap;
    if (frozen_joints_.update(joint_reading(sample, scratch))) c.status |= kStatusFrozenInput;
    c.stuck_pads = stuck_pads_.update(off_rail(sample.pressure, scratch));
    if (c.stuck_pads) c.status |= kStatusPadStuck;
    return c;
  }

  /// 1. q̈: the sample's where it has a finite one, else the filtered derivative of q̇ (the filter
  /// always runs, so it is warm when q̈ goes missing).
  struct Acceleration {
    const Vector*
        ddq;  ///< the sample's, or the filter's (both unchanged for the rest of the cycle)
    std::uint32_t status = 0;
  };
  Acceleration acceleration(const Sample& sample, S h) noexcept {
    const Vector& filtered = acceleration_.update(sample.dq, h);
    if (!sample.has_ddq) return {&filtered};
    if (all_finite(sample.ddq)) return {&sample.ddq};
    return {&filtered, kStatusAccelerationEstimated};
  }

  std::uint32_t range_status(const Sample& sample) const noexcept {
    for (int j = 0; j < joint_count(); ++j)
      if (sample.q[j] < nominal_.model.lower[j] - parameters_.position_margin_rad ||
          sample.q[j] > nominal_.model.upper[j] + parameters_.position_margin_rad)
        return kStatusPositionOutOfRange;
    return 0;
  }
  /// 2. Nominal model on the joint transforms (data_.liMi at q; the world poses wait for step 7):
  /// τ_res = τ_meas − τ_dyn − τ_fric.
  void nominal_residual(const Sample& sample, const Vector& ddq, Scratch& scratch) noexcept {
    Output& out = output_;
    joint_transforms(nominal_.model, data_, sample.q);
    predict_effort_at_pose(nominal_, links_, data_, sample.q, sample.dq, ddq, out.effort_rigid,
                           out.effort_friction, scratch.effort);
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

  /// 4. State machine, holding the last combined estimate for joints that stop in contact. The
  /// tracker has the model's coupling (constructor): at rest means every motor acting on the
  /// joint at rest.
  void update_state_machine(const Sample& sample) noexcept {
    tracker_.update(sample.t, sample.dq, output_.residual, skin_.any_contact(),
                    skin_.earliest_new_onset(), held_residual_);
    output_.state = tracker_.state();
    output_.static_friction = tracker_.friction_estimate();
  }

  /// 5. Compensator, prewarmed on the first sample with its steady input (q̈ = 0, no baseline).
  void compensate(const Sample& sample, const Vector& ddq, bool first, Scratch& scratch) noexcept {
    Output& out = output_;
    CompensatorInput<S, N>& x = scratch.compensator_input;
    if (first) {
      const Eigen::Index n = sample.q.size();
      x << sample.q, sample.dq, Vector::Zero(n), Vector::Zero(n), out.effort_friction;
      compensator_.reset(x);
    }
    compensator_input(sample.q, sample.dq, ddq, out.static_friction, out.effort_friction, x);
    out.compensation = compensator_.step(x);
  }

  /// 6. External torque two ways and combined: StaticModelFree on resting joints, Fused
  /// elsewhere (the nominal residual and band on joints outside the compensator's domain).
  /// Leaves the fused evidence in `fused`.
  void estimate_external_torque(const Sample& sample, const Vector& ddq, std::uint32_t& status,
                                FusedEvidence& fused) noexcept {
    Output& out = output_;
    const int n = joint_count();
    const std::uint32_t all = every_joint_mask(n);
    set_estimate(TorqueEstimator::StaticModelFree, tracker_.static_external(),
                 parameters_.static_dead_band, tracker_.valid_mask());
    fused.residual = out.residual - out.compensation;
    fused.sigma = moving_sigma_;
    fused.band = parameters_.dead_band_factor * parameters_.fused_sigma;
    fused.outside_band = false;
    for (int j = 0; j < n; ++j) {
      const bool outside = outside_compensator_domain(j, sample.dq[j], ddq[j]);
      const bool gated = !(compensated_joints_ & (1u << j));
      if (!outside && !gated) continue;
      fused.residual[j] = out.residual[j];
      fused.band[j] = parameters_.dead_band_factor * parameters_.nominal_sigma[j];
      fused.sigma[j] = nominal_moving_sigma_[j];
      status |=
          (outside ? kStatusOutsideCompensatorDomain : 0u) | (gated ? kStatusCompensatorGated : 0u);
    }
    set_estimate(TorqueEstimator::Fused, fused.residual, fused.band, all);
    const ExternalTorque<S, N>& fixed = out.estimate(TorqueEstimator::StaticModelFree);
    const ExternalTorque<S, N>& moving = out.estimate(TorqueEstimator::Fused);
    // Element by element: the values were just stored that way (a vector load of them would wait).
    for (int j = 0; j < n; ++j) {
      const bool use_static = fixed.valid & (1u << j);
      const S residual = use_static ? fixed.residual[j] : moving.residual[j];
      out.external.residual[j] = residual;
      out.external.torque[j] = use_static ? fixed.torque[j] : moving.torque[j];
      held_residual_[j] = residual;  // what a joint stopping next cycle holds
      fused.outside_band = fused.outside_band || residual != S(0);
    }
    out.external.valid = all;
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
  std::uint32_t estimate_wrench(Scratch& scratch) noexcept {
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
    const FusedEvidence& fused = scratch.fused;
    const ExternalTorque<S, N>& fixed = out.estimate(TorqueEstimator::StaticModelFree);
    const std::uint32_t held = tracker_.frozen_mask() & ~tracker_.onset_mask();
    Vector& evidence = scratch.evidence;
    Vector& sigma = scratch.evidence_sigma;
    for (int j = 0; j < joint_count(); ++j) {
      const bool at_rest = fixed.valid & (1u << j);
      const S r = at_rest ? tracker_.static_external()[j] : fused.residual[j];
      evidence[j] = -r;
      const S s = !at_rest             ? fused.sigma[j]
                  : (held & (1u << j)) ? held_sigma_[j]
                                       : static_sigma_[j];
      sigma[j] = s;
    }
    out.wrench =
        estimate_contact_force(jacobian_, pad_contact_frame_in_world(data_, g), evidence, sigma,
                               skin_.normal_force(pad), parameters_.wrench, scratch.contact);
    out.wrench.pad = pad;
    out.wrench.point_world = point;
    if (skin_.contact_count() == 1 && all_finite(out.wrench.force_world)) {
      out.external.torque.noalias() =
          jacobian_.template topRows<3>().transpose() * out.wrench.force_world;
      out.external.residual = -out.external.torque;
    }
    return out.wrench.valid ? 0u : std::uint32_t(kStatusWrenchUnobservable);
  }

  /// Finite t, q, q̇ and effort (and, with a start-up pad or joint count, vectors of that size).
  bool finite(const Sample& s) const noexcept {
    if constexpr (P == Eigen::Dynamic)
      if (s.pressure.size() != skin_.count()) return false;
    if constexpr (N == Eigen::Dynamic) {
      const Eigen::Index n = joint_count();
      if (s.q.size() != n || s.dq.size() != n || s.effort.size() != n ||
          (s.has_ddq && s.ddq.size() != n))
        return false;
    }
    return std::isfinite(s.t) && all_finite(s.q, s.dq, s.effort);
  }

  /// The pad readings for stuck detection: a reading on a rail (≤ 0 or ≥ full scale) is NaN, so
  /// it never counts as a repeat — a push that saturates the sensor is not a stuck pad.
  const Eigen::Matrix<S, P, 1>& off_rail(const Eigen::Matrix<S, P, 1>& p,
                                         Scratch& scratch) const noexcept {
    Eigen::Matrix<S, P, 1>& r = scratch.pressure;
    r = p;
    for (Eigen::Index k = 0; k < p.size(); ++k)
      if (!(p[k] > S(0) && p[k] < parameters_.skin.full_scale_kpa))
        r[k] = std::numeric_limits<S>::quiet_NaN();
    return r;
  }

  /// A joint's reading as one row: [q, q̇, effort].
  static const Eigen::Matrix<S, N, 3>& joint_reading(const Sample& s, Scratch& scratch) noexcept {
    Eigen::Matrix<S, N, 3>& r = scratch.joint_reading;
    r.col(0) = s.q;
    r.col(1) = s.dq;
    r.col(2) = s.effort;
    return r;
  }

  void update_sigmas() noexcept {
    const S floor = parameters_.wrench.torque_noise_nm;
    static_sigma_ = ((parameters_.static_dead_band / S(3)).cwiseAbs2() +
                     nominal_.friction.static_friction.cwiseAbs2() / S(3))
                        .cwiseSqrt()
                        .cwiseMax(floor);
    for (int j = 0; j < joint_count(); ++j) {
      const S fused = parameters_.fused_sigma[j], nominal = parameters_.nominal_sigma[j];
      nominal_moving_sigma_[j] = nominal > S(0) ? nominal : floor;
      moving_sigma_[j] = fused > S(0) ? fused : nominal_moving_sigma_[j];
      held_sigma_[j] = std::hypot(static_sigma_[j], moving_sigma_[j]);
    }
  }

  void start(const Sample& sample, Scratch& scratch) noexcept {
    started_ = true;
    frozen_joints_.reset(joint_reading(sample, scratch));
    stuck_pads_.reset(off_rail(sample.pressure, scratch));
    acceleration_.reset(sample.dq);
    Eigen::Matrix<S, P, 1>& p = scratch.pressure;
    p = sample.pressure;
    for (Eigen::Index k = 0; k < p.size(); ++k)
      if (!std::isfinite(p[k])) p[k] = S(0);
    skin_.reset(sample.t, p);
    skin_.set_ignored(0);
    tracker_.reset();
    torque_alarm_.reset();
    held_residual_.setZero();
    std::fill(outside_domain_.begin(), outside_domain_.end(), 0);
  }

  /// Estimate `which`: dead_band(x_j, width_j) on the joints of `valid`, 0 elsewhere.
  void set_estimate(TorqueEstimator which, const Vector& x, const Vector& width,
                    std::uint32_t valid) noexcept {
    ExternalTorque<S, N>& e = output_.estimates[static_cast<int>(which)];
    for (int j = 0; j < joint_count(); ++j) {
      const bool ok = valid & (1u << j);
      e.residual[j] = ok ? dead_band(x[j], width[j]) : S(0);
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
  std::uint32_t compensated_joints_ = 0;
  Jacobian<S, N> jacobian_ = zero_or_empty<Jacobian<S, N>>();
  Vector held_residual_ = zero_or_empty<Vector>();  ///< last torque-only estimate (StopPolicy)
  /// Per joint: cycles until its compensator input window is back inside the domain.
  LinkArray<int, N> outside_domain_{};
  Vector static_sigma_ = zero_or_empty<Vector>();
  Vector moving_sigma_ = zero_or_empty<Vector>();
  Vector nominal_moving_sigma_ = zero_or_empty<Vector>();  ///< σ_nominal (floor when uncalibrated)
  Vector held_sigma_ =
      zero_or_empty<Vector>();  ///< √(static² + moving²): a baseline held at a stop
  Output output_;
  [[no_unique_address]] std::conditional_t<kRunTimeSize, Scratch, NoScratch> scratch_;
  bool started_ = false;
};

}  // namespace tpf
