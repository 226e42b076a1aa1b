// The digital twin's main loop (see simulate.hpp and docs/twin.md).
//
// Coupled drives (a robot file's coupled_to, TwinArm::coupling C, motors × joints): each PH54
// drive servoes its own motor, as a real drive does with its motor's encoder. Drive m sees its
// motor's coordinate at the output scale, θ_m = (C·q)_m (reference (C·q_ref)_m, position and
// velocity quantised at that coordinate), its gains from the inertia its motor sees,
// (C⁻ᵀ·M·C⁻¹)_mm at the start pose, its clamps are its own current limit and its joint's
// velocity limit (applied to the motor's rate), and it starts holding gravity's motor torques
// C⁻ᵀ·G. Its current makes the motor torque K_t,m·i_m (output side), which acts on the joints
// as Cᵀ·(K_t·i). Since C is invertible, servoing every motor angle servoes every joint angle: the
// scripts stay in joint space (q_ref), and joint-space references become motor references
// through C. The motors' friction is the plant's (twin_plant.hpp: Cᵀ·F(C·q̇)); temperature and
// the undeclared coupling effect ((I + X)·K_t·i, then through Cᵀ) are per motor. Such a log
// holds the joint torques tau<j> = Cᵀ·K_t·i of the reported motor currents (N·m; a motor's
// current is no joint's, so no i<j>, as `tpf import` writes a coupled transmission's currents)
// and gt_fric<j> = (Cᵀ·F)_j in N·m. Without a coupling every step is the uncoupled twin's, bit
// for bit.
#include "offline/sim/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "offline/log/log_writer.hpp"
#include "offline/sim/admittance_controller.hpp"
#include "offline/sim/contact_script.hpp"
#include "offline/sim/excitation_schedule.hpp"
#include "offline/sim/human_hand.hpp"
#include "offline/sim/pad_sensors.hpp"
#include "offline/sim/ph54_drive.hpp"
#include "offline/sim/random.hpp"
#include "offline/sim/sensor_quantisation.hpp"
#include "offline/sim/twin_arm.hpp"
#include "offline/sim/twin_friction.hpp"
#include "offline/sim/twin_plant.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {

namespace {

constexpr double kPadRateHz = 1000.0;
constexpr double kLimitMargin = 0.05;  // rad kept clear of the joint limits by the scripts

std::string join(const TwinVector& v) {
  std::ostringstream s;
  s.precision(17);
  for (int j = 0; j < v.size(); ++j)
    s << (j ? "," : "") << v[j];
  return s.str();
}

// The timing of the host's 400 Hz cycle: nominal instants on the inner grid, some taken one
// inner step early or late (jitter), some lost (dropped rows), time stamps with a little noise.
class SampleClock {
 public:
  SampleClock(const SensorConfig& config, long ratio, Random rng)
      : config_(config), ratio_(ratio), rng_(std::move(rng)) {}

  /// Inner step index of the next cycle and whether the row is dropped.
  long next_step() const { return next_; }
  bool dropped() const { return dropped_; }
  void advance() {
    ++cycle_;
    long offset = 0;
    if (rng_.chance(config_.jitter_probability)) offset = rng_.chance(0.5) ? 1 : -1;
    next_ = cycle_ * ratio_ + offset;
    dropped_ = rng_.chance(config_.drop_probability);
  }
  /// Host time stamp of an instant, µs resolution, strictly increasing.
  double stamp(double t) {
    double s = std::round((t + config_.timestamp_noise_s * rng_.normal()) * 1e6) / 1e6;
    if (s <= last_stamp_) s = last_stamp_ + 1e-6;
    last_stamp_ = s;
    return s;
  }

 private:
  SensorConfig config_;
  long ratio_;
  Random rng_;
  long cycle_ = 0;
  long next_ = 0;
  bool dropped_ = false;
  double last_stamp_ = -1.0;
};

// Every per-joint vector of the scenario has one entry per joint of its robot (load_scenario
// makes them so; a scenario edited in code may not).
void check_sizes(const Scenario& s, int n) {
  const auto check = [&](const TwinVector& v, const char* key) {
    if (v.size() != n)
      throw Error::at(s.file.empty() ? s.robot_file : s.file, 0, key,
                      "has " + std::to_string(v.size()) + " values; the robot " + s.robot_file +
                          " has " + std::to_string(n) + " joints");
  };
  check(s.initial_q, "initial_q");
  check(s.effects.ripple.amplitude, "effects.ripple.amplitude_nm");
  check(s.effects.ripple.cycles_per_rev, "effects.ripple.cycles_per_rev");
  check(s.effects.ripple.phase, "effects.ripple.phase_rad");
  check(s.effects.spring.stiffness, "effects.spring.stiffness_nm_per_rad");
  check(s.effects.spring.neutral, "effects.spring.neutral_rad");
  check(s.excitation.lower, "excitation.lower_rad");
  check(s.excitation.upper, "excitation.upper_rad");
  if (s.effects.coupling.matrix.rows() != n || s.effects.coupling.matrix.cols() != n)
    throw Error::at(s.file.empty() ? s.robot_file : s.file, 0, "effects.coupling.matrix",
                    "must be " + std::to_string(n) + "×" + std::to_string(n));
}

// A scenario edited in code may start outside the joint limits (load_scenario refuses that).
void check_initial_pose(const Scenario& s, const TwinArm& arm) {
  for (int j = 0; j < arm.joints(); ++j) {
    const double q = s.initial_q[j];
    if (q >= arm.lower()[j] && q <= arm.upper()[j]) continue;
    std::ostringstream m;
    m << q << " rad is outside the limits of joint " << j + 1 << ", [" << arm.lower()[j] << ", "
      << arm.upper()[j] << "] rad, of the robot " << s.robot_file;
    throw Error::at(s.file.empty() ? s.robot_file : s.file, 0,
                    "initial_q[" + std::to_string(j) + "]", m.str());
  }
}

// The twin's true friction: the scenario's friction file, none (all zero) when its effects turn
// friction off.
TwinFriction true_friction(const Scenario& s, int joints) {
  if (s.effects.friction == EffectsConfig::Friction::kNone)
    return TwinFriction{std::vector<JointFriction>(static_cast<std::size_t>(joints))};
  if (s.friction_file.empty())
    throw Error::at(s.file.empty() ? s.robot_file : s.file, 0, "friction",
                    "no friction file, and effects.friction is not \"none\"");
  return load_twin_friction(s.friction_file, joints);
}

}  // namespace

std::vector<std::string> simulation_columns(int joints, int pad_count, bool coupled) {
  std::vector<std::string> c{"t"};
  for (const char* prefix : {"q", "dq", coupled ? "tau" : "i"})
    for (int j = 1; j <= joints; ++j)
      c.push_back(indexed_name(prefix, j));
  for (int k = 1; k <= pad_count; ++k)
    c.push_back(indexed_name("p", k));
  for (const char* prefix : {"temp", "gt_fric", "gt_tau_ext", "gt_ddq"})
    for (int j = 1; j <= joints; ++j)
      c.push_back(indexed_name(prefix, j));
  for (const char* name : {"gt_contact", "gt_fx", "gt_fy", "gt_fz"})
    c.push_back(name);
  return c;
}

std::vector<std::string> simulation_columns(const Scenario& scenario) {
  const TwinArm arm(scenario);
  return simulation_columns(scenario.joints, arm.pad_count(), arm.coupled());
}

LogMetadata simulation_metadata(const Scenario& s, std::uint64_t seed, double duration_s) {
  const TwinArm arm(s);
  LogMetadata m;
  m.set("tpf-log", "1");
  m.set("robot", arm.name());
  std::ostringstream rate;
  rate << s.log_rate_hz;
  m.set("rate_hz", rate.str());
  m.set("source", "simulated (tpf digital twin)");
  m.set("seed", std::to_string(seed));
  m.set("scenario",
        s.name + " (" + to_string(s.kind) + (s.file.empty() ? "" : ", " + s.file) + ")");
  std::ostringstream d;
  d << duration_s;
  m.set("duration_s", d.str());
  m.set("torque_constant_nm_per_a", join(arm.torque_constant()));
  m.set("friction_file", s.effects.friction == EffectsConfig::Friction::kNone
                             ? std::string("none (effects.friction)")
                             : s.friction_file);
  if (arm.coupled()) {
    m.set("note",
          "coupled drives (the robot file's coupled_to): tau<j> are the joint torques C^T*K_t*i "
          "of the motors' currents, N*m; ground truth in gt_* columns; gt_fric in N*m on the "
          "joints (C^T*F of the motors' friction), gt_tau_ext in N*m (torque the environment "
          "applies to the robot), gt_f* in N, world frame");
  } else {
    m.set("note",
          "ground truth in gt_* columns; gt_fric in mA, gt_tau_ext in N*m (torque the "
          "environment applies to the robot), gt_f* in N, world frame");
  }
  return m;
}

SimulationSummary simulate(const Scenario& scenario, std::uint64_t seed, double duration_s,
                           const RowSink& sink, const ProgressSink& progress,
                           const ExternalTorqueSource& external_torque) {
  const double duration = duration_s > 0 ? duration_s : scenario.duration_s;
  const double h = 1.0 / scenario.inner_rate_hz;
  const long ratio = std::lround(scenario.inner_rate_hz / scenario.log_rate_hz);
  const long total_steps = std::lround(duration * scenario.inner_rate_hz);
  const long pad_every = std::max(1L, std::lround(scenario.inner_rate_hz / kPadRateHz));
  const auto& fx = scenario.effects;

  Random root(seed);
  Random plan_rng = root.split(), sensor_rng = root.split(), hand_rng = root.split();

  const TwinArm arm(scenario);
  Scenario nominal_scenario = scenario;
  nominal_scenario.effects.payload.enabled = false;
  const TwinArm nominal(nominal_scenario);
  const int joints = arm.joints();
  check_sizes(scenario, joints);
  check_initial_pose(scenario, arm);
  const TwinFriction friction = true_friction(scenario, joints);
  const int pads = arm.pad_count();
  if (scenario.kind == Scenario::Kind::kTeaching && pads == 0)
    throw Error::at(scenario.file, 0, "kind",
                    "teaching needs a robot with skin pads (the hand holds a pad); " +
                        scenario.robot_file + " has none");

  // Script ranges: the scenario's range inside the joint limits.
  const TwinVector lower =
      scenario.excitation.lower.cwiseMax(arm.lower() + TwinVector::Constant(joints, kLimitMargin));
  const TwinVector upper =
      scenario.excitation.upper.cwiseMin(arm.upper() - TwinVector::Constant(joints, kLimitMargin));

  for (int j = 0; j < joints; ++j)
    if (!(lower[j] < upper[j]))
      throw Error::at(scenario.file, 0, "excitation.lower_rad[" + std::to_string(j) + "]",
                      "the range lies outside the joint limits of " + scenario.robot_file);

  TwinPlant plant(arm, friction, fx, h);
  plant.reset(scenario.initial_q, TwinVector::Zero(joints));
  // Coupled drives servo their motors' coordinates C·q (see the file's header).
  const bool coupled = arm.coupled();
  const TwinMatrix& motor_coupling = arm.coupling();
  std::optional<Ph54Drive> drive_storage;
  if (coupled) {
    const TwinMatrix inverse = motor_coupling.inverse();
    const TwinMatrix motor_inertia =
        inverse.transpose() * arm.mass_matrix(scenario.initial_q) * inverse;
    drive_storage.emplace(scenario.drive, motor_inertia.diagonal(), arm.torque_constant(),
                          arm.current_limit(), arm.velocity_limit());
    drive_storage->reset((inverse.transpose() * arm.gravity(scenario.initial_q))
                             .cwiseQuotient(arm.torque_constant()));
  } else {
    drive_storage.emplace(scenario.drive, arm.mass_matrix(scenario.initial_q).diagonal(),
                          arm.torque_constant(), arm.current_limit(), arm.velocity_limit());
    drive_storage->reset(arm.gravity(scenario.initial_q).cwiseQuotient(arm.torque_constant()));
  }
  Ph54Drive& drive = *drive_storage;

  std::optional<MinJerkSchedule> schedule;
  std::optional<ContactScript> contacts;
  std::optional<HumanHand> hand;
  std::optional<AdmittanceController> admittance;
  switch (scenario.kind) {
    case Scenario::Kind::kExcitation:
      schedule = make_excitation_schedule(scenario.excitation, scenario.initial_q, lower, upper,
                                          duration, plan_rng);
      break;
    case Scenario::Kind::kStaticContacts: {
      auto plan = make_static_contact_plan(scenario.contacts, scenario.initial_q, lower, upper,
                                           pads, duration, plan_rng);
      schedule = std::move(plan.poses);
      contacts = std::move(plan.contacts);
      break;
    }
    case Scenario::Kind::kTeaching:
      hand.emplace(scenario.teaching, lower, upper, hand_rng);
      admittance.emplace(scenario.teaching, friction, scenario.initial_q, lower, upper);
      break;
  }

  PadSensors pad_sensors(scenario.pads, pads, root.split());
  SampleClock clock(scenario.sensors, ratio, root.split());
  std::vector<double> pad_force(pads, 0.0), pad_area(pads, 1.0);

  // Delay line between the drive's current and the torque it produces (undeclared effect): a ring
  // of delay_steps + 1 currents, the one pushed delay_steps steps ago (the first, until then).
  const long delay_steps = fx.delay.enabled ? std::lround(fx.delay.delay_s / h) : 0;
  std::vector<TwinVector> delay_line(
      static_cast<std::size_t>(delay_steps > 0 ? delay_steps + 1 : 0), TwinVector::Zero(joints));
  long delay_pushed = 0;
  TwinVector temperature = TwinVector::Constant(joints, fx.thermal.initial_c);
  const TwinMatrix coupling =
      TwinMatrix::Identity(joints, joints) +
      (fx.coupling.enabled ? fx.coupling.matrix : TwinMatrix::Zero(joints, joints));

  const auto columns = simulation_columns(joints, pads);
  std::vector<double> row(columns.size());
  SimulationSummary summary;
  TwinVector q_ref = scenario.initial_q, dq_ref = TwinVector::Zero(joints);
  double last_host_update = 0.0;
  // The loop's vectors, sized once: a step allocates nothing (plant and drive included).
  TwinVector tau_ext(joints), q_meas(joints), dq_meas(joints), i_meas(joints);
  TwinVector q_drive(joints), dq_drive(joints), current(joints), motor_current(joints);
  TwinVector tau_motor(joints), tau_in(joints), viscous_scale(joints);
  TwinVector motor_ref(joints), motor_dref(joints), motor_q(joints), motor_dq(joints);
  TwinVector effort(joints), tau_joint(joints);  // coupled: logged and applied joint torques
  PadFrame frame;
  frame.linear_jacobian.setZero(3, joints);

  for (long n = 0; n <= total_steps; ++n) {
    const double t = n * h;
    const TwinVector& q = plant.q();
    const TwinVector& dq = plant.dq();

    // Contact force on the robot, world frame, and its joint torque τ_ext = J_vᵀ·F.
    int contact_pad = -1;
    Vector3<double> force = Vector3<double>::Zero();
    double area = 1.0;
    if (contacts) {
      const ContactSample c = contacts->at(t);
      if (c.pad >= 0) {
        contact_pad = c.pad;
        arm.pad_frame(q, c.pad, frame);
        force = frame.rotation * c.force_contact;
        area = c.area_cm2;
      }
    } else if (hand) {
      const HandForce f = hand->update(arm, t, q, dq);
      contact_pad = f.pad;
      force = f.force_world;
      area = f.area_cm2;
    }
    tau_ext.setZero();
    if (contact_pad >= 0) {
      arm.pad_frame(q, contact_pad, frame);
      multiply_transposed(frame.linear_jacobian, force, tau_ext);
      std::fill(pad_force.begin(), pad_force.end(), 0.0);
      pad_force[contact_pad] = -force.dot(frame.rotation.col(2));
      pad_area[contact_pad] = area;
    } else {
      std::fill(pad_force.begin(), pad_force.end(), 0.0);
    }
    if (n % pad_every == 0) pad_sensors.update(pad_force, pad_area, pad_every * h);

    // The host's cycle: what the drives and the pad board report.
    if (n == clock.next_step()) {
      const double stamp = clock.stamp(t);
      for (int j = 0; j < joints; ++j) {
        q_meas[j] = quantise_position(q[j]);
        dq_meas[j] = quantise_velocity(dq[j]);
        i_meas[j] = quantise_current_ma(drive.current()[j] * 1000.0 +
                                        scenario.sensors.current_noise_ma * sensor_rng.normal());
      }
      if (!clock.dropped()) {
        std::size_t c = 0;
        row[c++] = stamp;
        if (coupled) {  // the joints' torques Cᵀ·K_t·i of the reported motor currents, N·m
          for (int j = 0; j < joints; ++j) {
            double sum = 0.0;
            for (int m = 0; m < joints; ++m)
              sum += motor_coupling(m, j) * arm.torque_constant()[m] * i_meas[m] / 1000.0;
            effort[j] = sum;
          }
        }
        for (const TwinVector* v : {&q_meas, &dq_meas, coupled ? &effort : &i_meas})
          for (int j = 0; j < joints; ++j)
            row[c++] = (*v)[j];
        double max_pad = 0.0;
        for (int k = 0; k < pads; ++k) {
          row[c++] = pad_sensors.reading(k);
          max_pad = std::max(max_pad, pad_sensors.reading(k));
        }
        for (int j = 0; j < joints; ++j)
          row[c++] = std::round(temperature[j]);
        for (int j = 0; j < joints; ++j)
          row[c++] = coupled ? plant.friction()[j]
                             : plant.friction()[j] / arm.torque_constant()[j] * 1000.0;
        for (int j = 0; j < joints; ++j)
          row[c++] = tau_ext[j];
        for (int j = 0; j < joints; ++j)
          row[c++] = plant.ddq()[j];
        row[c++] = contact_pad + 1;
        for (int a = 0; a < 3; ++a)
          row[c++] = force[a];
        sink(row);
        ++summary.rows;
        if (admittance && external_torque) {
          admittance->follow(external_torque(row), max_pad, t - last_host_update);
          last_host_update = t;
        } else if (admittance) {
          admittance->update(nominal, q_meas, dq_meas, i_meas, max_pad, t - last_host_update);
          last_host_update = t;
        }
      } else {
        ++summary.dropped_rows;
      }
      clock.advance();
    }
    if (n == total_steps) break;

    // Reference, drive, torque, mechanics, heat.
    if (schedule) {
      schedule->evaluate(t, q_ref, dq_ref);
    } else if (admittance) {
      admittance->goal(t - last_host_update, q_ref, dq_ref);  // first-order hold, see goal()
    }
    if (coupled) {  // each drive on its motor's coordinate (C·q)_m
      multiply(motor_coupling, q_ref, motor_ref);
      multiply(motor_coupling, dq_ref, motor_dref);
      multiply(motor_coupling, q, motor_q);
      multiply(motor_coupling, dq, motor_dq);
      for (int m = 0; m < joints; ++m) {
        q_drive[m] = quantise_position(motor_q[m]);
        dq_drive[m] = quantise_velocity(motor_dq[m]);
      }
      current = drive.update(motor_ref, motor_dref, q_drive, dq_drive, h);
    } else {
      for (int j = 0; j < joints; ++j) {
        q_drive[j] = quantise_position(q[j]);
        dq_drive[j] = quantise_velocity(dq[j]);
      }
      current = drive.update(q_ref, dq_ref, q_drive, dq_drive, h);
    }
    if (delay_steps > 0) {
      const auto slots = static_cast<long>(delay_line.size());
      delay_line[static_cast<std::size_t>(delay_pushed % slots)] = current;
      current = delay_line[static_cast<std::size_t>(
          delay_pushed >= delay_steps ? (delay_pushed - delay_steps) % slots : 0)];
      ++delay_pushed;
    }
    motor_current = arm.torque_constant().cwiseProduct(current);
    multiply(coupling, motor_current, tau_motor);
    viscous_scale.setOnes();
    if (fx.thermal.enabled)
      viscous_scale = (TwinVector::Ones(joints) +
                       fx.thermal.viscous_per_k *
                           (temperature - TwinVector::Constant(joints, fx.thermal.initial_c)))
                          .cwiseMax(0.1);
    if (coupled) {  // the motors' torques on the joints, Cᵀ·τ_motor
      for (int j = 0; j < joints; ++j) {
        double sum = 0.0;
        for (int m = 0; m < joints; ++m)
          sum += motor_coupling(m, j) * tau_motor[m];
        tau_joint[j] = sum;
      }
      tau_in = tau_joint + tau_ext;
    } else {
      tau_in = tau_motor + tau_ext;
    }
    plant.step(tau_in, viscous_scale);
    if (!plant.q().allFinite() || !plant.dq().allFinite())
      throw Error::at(scenario.robot_file, 0, "",
                      "the twin's state is no longer finite at t = " + std::to_string(n * h) +
                          " s: its mass matrix is singular (a link without mass and a "
                          "rotor_inertia of 0: `tpf info` prints M_jj) or a value is far out of "
                          "range; nothing was written");
    const TwinVector& i_now = drive.current();
    temperature += h * (fx.thermal.heating_k_per_a2s * i_now.cwiseProduct(i_now) -
                        (temperature - TwinVector::Constant(joints, fx.thermal.ambient_c)) /
                            fx.thermal.time_constant_s);

    if (progress && n % static_cast<long>(scenario.inner_rate_hz) == 0)
      progress(static_cast<double>(n) / static_cast<double>(total_steps));
  }
  if (progress) progress(1.0);
  summary.simulated_s = duration;
  return summary;
}

SimulationSummary simulate_to_file(const Scenario& scenario, std::uint64_t seed, double duration_s,
                                   const std::filesystem::path& path,
                                   const ProgressSink& progress) {
  const double duration = duration_s > 0 ? duration_s : scenario.duration_s;
  LogWriter writer(path, simulation_metadata(scenario, seed, duration),
                   simulation_columns(scenario));
  const auto summary = simulate(
      scenario, seed, duration, [&](std::span<const double> row) { writer.write_row(row); },
      progress);
  writer.close();
  return summary;
}

Log simulate_to_log(const Scenario& scenario, std::uint64_t seed, double duration_s,
                    const ExternalTorqueSource& external_torque) {
  const double duration = duration_s > 0 ? duration_s : scenario.duration_s;
  Log log;
  log.source = "simulated";
  log.columns = simulation_columns(scenario);
  log.meta = simulation_metadata(scenario, seed, duration);
  std::vector<double> values;
  const auto summary = simulate(
      scenario, seed, duration,
      [&](std::span<const double> row) { values.insert(values.end(), row.begin(), row.end()); }, {},
      external_torque);
  const auto cols = static_cast<Eigen::Index>(log.columns.size());
  log.values =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          values.data(), static_cast<Eigen::Index>(summary.rows), cols);
  return log;
}

}  // namespace tpf::offline
