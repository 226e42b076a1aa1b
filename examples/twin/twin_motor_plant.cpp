#include "twin/twin_motor_plant.hpp"

#include <algorithm>
#include <cmath>

#include "offline/sim/pad_sensors.hpp"
#include "offline/sim/ph54_drive.hpp"
#include "offline/sim/random.hpp"
#include "offline/sim/sensor_quantisation.hpp"
#include "offline/sim/twin_arm.hpp"
#include "offline/sim/twin_friction.hpp"
#include "offline/sim/twin_plant.hpp"

namespace tpf::dxl::emu {

using offline::TwinVector;

namespace {
constexpr double kPadRateHz = 1000.0;  // the Teensy's sampling rate (hardware.md §5)
}  // namespace

struct TwinMotorPlant::Twin {
  offline::Scenario scenario;
  offline::TwinArm arm;
  offline::TwinPlant plant;
  std::vector<offline::Ph54Drive> drives;  // one per joint (joint j uses entry j of drive j)
  TwinVector current;                      // motor current, A
  offline::PadSensors pads;
  offline::ContactScript contacts;
  offline::Random noise;
  std::vector<double> pad_force, pad_area;

  Twin(const offline::Scenario& s, offline::Random& root)
      : scenario(s),
        arm(s),
        plant(arm, offline::load_twin_friction(s.friction_file, arm.joints()), s.effects,
              1.0 / s.inner_rate_hz),
        drives(
            static_cast<std::size_t>(arm.joints()),
            offline::Ph54Drive(s.drive, arm.mass_matrix(s.initial_q).diagonal(),
                               arm.torque_constant(), arm.current_limit(), arm.velocity_limit())),
        pads(s.pads, arm.pad_count(), root.split()),
        noise(root.split()),
        pad_force(static_cast<std::size_t>(arm.pad_count()), 0.0),
        pad_area(static_cast<std::size_t>(arm.pad_count()), 1.0) {}
};

TwinMotorPlant::TwinMotorPlant(const offline::Scenario& scenario, TwinMotorPlantOptions options)
    : options_(options) {
  offline::Random root(options.seed);
  offline::Random plan_rng = root.split();
  twin_ = std::make_unique<Twin>(scenario, root);
  h_ = 1.0 / scenario.inner_rate_hz;
  pad_every_ = std::max(1L, std::lround(scenario.inner_rate_hz / kPadRateHz));
  const int joints = twin_->arm.joints();
  twin_->current.setZero(joints);
  twin_->plant.reset(scenario.initial_q, TwinVector::Zero(joints));
  was_enabled_.assign(static_cast<std::size_t>(joints), false);
  state_.assign(static_cast<std::size_t>(joints), MotorState{});
  if (scenario.kind == offline::Scenario::Kind::kStaticContacts) {
    const TwinVector& lower = twin_->arm.lower();
    const TwinVector& upper = twin_->arm.upper();
    twin_->contacts =
        offline::make_static_contact_plan(scenario.contacts, scenario.initial_q, lower, upper,
                                          twin_->arm.pad_count(), scenario.duration_s, plan_rng)
            .contacts;
  }
  pad_kpa_.assign(static_cast<std::size_t>(twin_->arm.pad_count()), 0.0f);
  truth_.reserve(options_.truth_capacity);
  for (int j = 0; j < joints; ++j)
    state_[static_cast<std::size_t>(j)].position_rad = scenario.initial_q[j];
}

TwinMotorPlant::~TwinMotorPlant() = default;

void TwinMotorPlant::set_contacts(offline::ContactScript contacts) {
  twin_->contacts = std::move(contacts);
}

int TwinMotorPlant::pad_count() const {
  return static_cast<int>(pad_kpa_.size());
}

int TwinMotorPlant::pad_pressures(std::span<float> kpa) const {
  std::lock_guard lock(pads_mutex_);
  const std::size_t n = std::min(kpa.size(), pad_kpa_.size());
  std::copy_n(pad_kpa_.begin(), n, kpa.begin());
  return static_cast<int>(n);
}

void TwinMotorPlant::step(double dt, std::span<const MotorGoal> goals) {
  pending_ += dt;
  while (pending_ >= h_) {
    inner_step(goals);
    pending_ -= h_;
  }
}

void TwinMotorPlant::inner_step(std::span<const MotorGoal> goals) {
  Twin& w = *twin_;
  const TwinVector& q = w.plant.q();

  // The scripted push: force on the robot in the world frame, τ_ext = J_vᵀ·F.
  TwinTruth truth;
  truth.t = t_;
  truth.q = q;
  truth.tau_ext.setZero(q.size());
  const offline::ContactSample c = w.contacts.at(t_);
  std::fill(w.pad_force.begin(), w.pad_force.end(), 0.0);
  if (c.pad >= 0) {
    const offline::PadFrame frame = w.arm.pad_frame(q, c.pad);
    const Vector3<double> force = frame.rotation * c.force_contact;
    truth.tau_ext = offline::multiply_transposed(frame.linear_jacobian, force);
    truth.pad = c.pad;
    truth.normal_force_n = -force.dot(frame.rotation.col(2));
    w.pad_force[static_cast<std::size_t>(c.pad)] = truth.normal_force_n;
    w.pad_area[static_cast<std::size_t>(c.pad)] = c.area_cm2;
  }
  if (steps_ % pad_every_ == 0) {
    w.pads.update(w.pad_force, w.pad_area, static_cast<double>(pad_every_) * h_);
    std::lock_guard lock(pads_mutex_);
    for (std::size_t k = 0; k < pad_kpa_.size(); ++k)
      pad_kpa_[k] = static_cast<float>(w.pads.reading(static_cast<int>(k)));
  }
  if (truth_.size() < truth_.capacity()) truth_.push_back(truth);

  for (const MotorGoal& g : goals)
    powered_ = powered_ || g.torque_enabled;
  if (powered_) {  // until then the arm rests at the initial pose, supported
    motor_current(goals);
    const TwinVector tau_motor = w.arm.torque_constant().cwiseProduct(w.current);
    w.plant.step(tau_motor + truth.tau_ext, TwinVector::Ones(w.arm.joints()));
    stop_at_limits();
  }
  t_ += h_;
  ++steps_;

  for (int j = 0; j < w.arm.joints(); ++j) {
    state_[j].position_rad = w.plant.q()[j];
    state_[j].velocity_rad_s = w.plant.dq()[j];
    state_[j].current_A =
        w.current[j] + 1e-3 * w.scenario.sensors.current_noise_ma * w.noise.normal();
  }
}

void TwinMotorPlant::motor_current(std::span<const MotorGoal> goals) {
  Twin& w = *twin_;
  const TwinVector& q = w.plant.q();
  const TwinVector& dq = w.plant.dq();
  TwinVector q_meas(q.size()), dq_meas(q.size());  // what the drive's encoder reports
  for (int j = 0; j < w.arm.joints(); ++j) {
    q_meas[j] = offline::quantise_position(q[j]);
    dq_meas[j] = offline::quantise_velocity(dq[j]);
  }
  const double lag = 1.0 - std::exp(-h_ / std::max(w.scenario.drive.current_time_constant, 1e-9));
  for (int j = 0; j < w.arm.joints(); ++j) {
    const auto k = static_cast<std::size_t>(j);
    const MotorGoal g = k < goals.size() ? goals[k] : MotorGoal{};
    if (!g.torque_enabled) {
      w.current[j] = 0.0;
    } else if (g.mode == ph54::OperatingMode::current) {
      const double limit = w.arm.current_limit()[j];
      w.current[j] += lag * (std::clamp(g.current_A, -limit, limit) - w.current[j]);
    } else {
      // Switched on: the cascade starts from rest (integrator 0), as the PH54 does.
      if (!was_enabled_[j]) w.drives[j].reset(TwinVector::Zero(w.arm.joints()));
      TwinVector q_ref = q_meas, dq_ref = TwinVector::Zero(w.arm.joints());
      if (g.mode == ph54::OperatingMode::velocity)
        dq_ref[j] = g.velocity_rad_s;
      else
        q_ref[j] = g.position_rad;
      w.current[j] = w.drives[j].update(q_ref, dq_ref, q_meas, dq_meas, h_)[j];
    }
    was_enabled_[j] = g.torque_enabled;
  }
}

void TwinMotorPlant::stop_at_limits() {
  Twin& w = *twin_;
  TwinVector q = w.plant.q(), dq = w.plant.dq();
  bool hit = false;
  for (int j = 0; j < w.arm.joints(); ++j) {
    if (q[j] < w.arm.lower()[j] && dq[j] < 0.0) {
      q[j] = w.arm.lower()[j];
      dq[j] = 0.0;
      hit = true;
    } else if (q[j] > w.arm.upper()[j] && dq[j] > 0.0) {
      q[j] = w.arm.upper()[j];
      dq[j] = 0.0;
      hit = true;
    }
  }
  if (hit) w.plant.reset(q, dq);  // an inelastic mechanical stop
}

}  // namespace tpf::dxl::emu
