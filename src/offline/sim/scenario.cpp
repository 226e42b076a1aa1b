// Scenario file loading (see scenario.hpp and docs/twin.md).
#include "offline/sim/scenario.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/common/json_object.hpp"
#include "offline/common/data_files.hpp"
#include "tpf/common/error.hpp"
#include "tpf/model/robot_description.hpp"

namespace tpf::offline {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// A per-joint vector: exactly one value per joint of the robot (`fallback` has that size).
TwinVector vector_of(json::Object& o, const std::string& key, const TwinVector& fallback, double lo,
                     double hi) {
  const auto n = static_cast<std::size_t>(fallback.size());
  const auto v = o.numbers(key, {fallback.data(), fallback.data() + n}, lo, hi, n);
  return TwinVector::Map(v.data(), fallback.size());
}

// Reads lo/hi keys of a range and checks lo <= hi.
void range(json::Object& o, const std::string& lo_key, const std::string& hi_key, double& lo,
           double& hi, double min, double max) {
  lo = o.number(lo_key, lo, min, max);
  hi = o.number(hi_key, hi, min, max);
  if (lo > hi) o.fail(hi_key, "must not be smaller than " + lo_key);
}

// The file `key` names (relative to the scenario's folder), or `fallback` when absent.
std::string resolve(json::Object& o, const std::string& key, const std::filesystem::path& dir,
                    const std::string& fallback) {
  const std::string value = o.text(key, "");
  if (value.empty()) return fallback;
  std::filesystem::path p(value);
  if (p.is_relative()) p = dir / p;
  if (!std::filesystem::exists(p)) o.fail(key, "file not found: " + p.string());
  return p.lexically_normal().string();
}

void read_drive(json::Object o, DriveConfig& d) {
  d.enabled = o.boolean("enabled", d.enabled);
  d.position_bandwidth_hz = o.number("position_bandwidth_hz", d.position_bandwidth_hz, 0.0, 50.0);
  d.velocity_bandwidth_hz = o.number("velocity_bandwidth_hz", d.velocity_bandwidth_hz, 0.1, 200.0);
  d.integral_corner_hz = o.number("integral_corner_hz", d.integral_corner_hz, 0.0, 50.0);
  d.velocity_feedforward = o.number("velocity_feedforward", d.velocity_feedforward, 0.0, 1.5);
  d.current_time_constant = o.number("current_time_constant_s", d.current_time_constant, 0.0, 0.05);
  o.finish();
}

void read_sensors(json::Object o, SensorConfig& s) {
  s.current_noise_ma = o.number("current_noise_ma", s.current_noise_ma, 0.0, 1000.0);
  s.jitter_probability = o.number("jitter_probability", s.jitter_probability, 0.0, 1.0);
  s.timestamp_noise_s = o.number("timestamp_noise_s", s.timestamp_noise_s, 0.0, 2e-4);
  s.drop_probability = o.number("drop_probability", s.drop_probability, 0.0, 0.5);
  o.finish();
}

void read_pads(json::Object o, PadSensorConfig& p) {
  p.time_constant_s = o.number("time_constant_s", p.time_constant_s, 1e-4, 1.0);
  p.gain_kpa_per_n = o.number("gain_kpa_per_n", p.gain_kpa_per_n, 0.0, 100.0);
  p.reference_area_cm2 = o.number("reference_area_cm2", p.reference_area_cm2, 0.01, 1000.0);
  p.area_exponent = o.number("area_exponent", p.area_exponent, 0.0, 2.0);
  p.noise_kpa = o.number("noise_kpa", p.noise_kpa, 0.0, 10.0);
  p.drift_kpa_per_sqrt_s = o.number("drift_kpa_per_sqrt_s", p.drift_kpa_per_sqrt_s, 0.0, 10.0);
  p.full_scale_kpa = o.number("full_scale_kpa", p.full_scale_kpa, 1.0, 1000.0);
  p.adc_step_kpa = o.number("adc_step_kpa", p.adc_step_kpa, 0.0, 1.0);
  o.finish();
}

void read_effects(json::Object o, EffectsConfig& e) {
  const std::string f = o.choice("friction", "lugre", {"lugre", "stribeck", "none"});
  e.friction = f == "lugre"      ? EffectsConfig::Friction::kLuGre
               : f == "stribeck" ? EffectsConfig::Friction::kStribeck
                                 : EffectsConfig::Friction::kNone;
  e.load_dependent_friction = o.boolean("load_dependent_friction", e.load_dependent_friction);
  e.gravity = o.boolean("gravity", e.gravity);
  {
    json::Object r = o.child("ripple");
    e.ripple.enabled = r.boolean("enabled", e.ripple.enabled);
    e.ripple.amplitude = vector_of(r, "amplitude_nm", e.ripple.amplitude, 0.0, 50.0);
    e.ripple.cycles_per_rev = vector_of(r, "cycles_per_rev", e.ripple.cycles_per_rev, 0.0, 1e4);
    e.ripple.phase = vector_of(r, "phase_rad", e.ripple.phase, -10.0, 10.0);
    r.finish();
  }
  {
    json::Object p = o.child("payload");
    e.payload.enabled = p.boolean("enabled", e.payload.enabled);
    e.payload.mass = p.number("mass_kg", e.payload.mass, 0.0, 10.0);
    const auto x = p.numbers("position_m", {0.0, 0.0, 0.0}, -1.0, 1.0, 3);
    e.payload.position = Vector3<double>(x[0], x[1], x[2]);
    p.finish();
  }
  {
    json::Object t = o.child("thermal");
    e.thermal.enabled = t.boolean("enabled", e.thermal.enabled);
    e.thermal.ambient_c = t.number("ambient_c", e.thermal.ambient_c, -20.0, 60.0);
    e.thermal.initial_c = t.number("initial_c", e.thermal.initial_c, -20.0, 80.0);
    e.thermal.heating_k_per_a2s =
        t.number("heating_k_per_a2s", e.thermal.heating_k_per_a2s, 0.0, 10.0);
    e.thermal.time_constant_s = t.number("time_constant_s", e.thermal.time_constant_s, 1.0, 1e6);
    e.thermal.viscous_per_k = t.number("viscous_per_k", e.thermal.viscous_per_k, -0.05, 0.05);
    t.finish();
  }
  {
    json::Object s = o.child("spring");
    e.spring.enabled = s.boolean("enabled", e.spring.enabled);
    e.spring.stiffness = vector_of(s, "stiffness_nm_per_rad", e.spring.stiffness, 0.0, 1e3);
    e.spring.neutral = vector_of(s, "neutral_rad", e.spring.neutral, -10.0, 10.0);
    s.finish();
  }
  {
    json::Object d = o.child("delay");
    e.delay.enabled = d.boolean("enabled", e.delay.enabled);
    e.delay.delay_s = d.number("delay_s", e.delay.delay_s, 0.0, 0.1);
    d.finish();
  }
  {
    json::Object c = o.child("coupling");
    e.coupling.enabled = c.boolean("enabled", e.coupling.enabled);
    const auto n = static_cast<int>(e.coupling.matrix.rows());
    std::vector<double> fallback(static_cast<std::size_t>(n * n));
    for (int r = 0; r < n; ++r)
      for (int k = 0; k < n; ++k)
        fallback[static_cast<std::size_t>(r * n + k)] = e.coupling.matrix(r, k);
    const auto m = c.numbers("matrix", fallback, -0.5, 0.5, fallback.size());
    for (int r = 0; r < n; ++r)
      for (int k = 0; k < n; ++k)
        e.coupling.matrix(r, k) = m[static_cast<std::size_t>(r * n + k)];
    c.finish();
  }
  o.finish();
}

void read_excitation(json::Object o, ExcitationConfig& x) {
  range(o, "rest_min_s", "rest_max_s", x.rest_min_s, x.rest_max_s, 0.0, 60.0);
  range(o, "move_min_rad", "move_max_rad", x.move_min_rad, x.move_max_rad, 1e-4, 6.0);
  range(o, "speed_min", "speed_max", x.speed_min, x.speed_max, 1e-3, 3.0);
  x.lower = vector_of(o, "lower_rad", x.lower, -3.2, 3.2);
  x.upper = vector_of(o, "upper_rad", x.upper, -3.2, 3.2);
  for (int j = 0; j < x.lower.size(); ++j)
    if (x.upper[j] - x.lower[j] < x.move_max_rad)
      o.fail("upper_rad[" + std::to_string(j) + "]",
             "range narrower than move_max_rad; widen it or shorten the moves");
  o.finish();
}

void read_contacts(json::Object o, ContactConfig& c) {
  range(o, "force_min_n", "force_max_n", c.force_min_n, c.force_max_n, 0.0, 200.0);
  c.shear_ratio_max = o.number("shear_ratio_max", c.shear_ratio_max, 0.0, 2.0);
  range(o, "area_min_cm2", "area_max_cm2", c.area_min_cm2, c.area_max_cm2, 0.01, 1000.0);
  c.ramp_s = o.number("ramp_s", c.ramp_s, 0.01, 5.0);
  range(o, "hold_min_s", "hold_max_s", c.hold_min_s, c.hold_max_s, 0.0, 60.0);
  range(o, "pause_min_s", "pause_max_s", c.pause_min_s, c.pause_max_s, 0.0, 60.0);
  c.pushes_per_pose = static_cast<int>(o.number("pushes_per_pose", c.pushes_per_pose, 1, 100));
  c.pose_move_s = o.number("pose_move_s", c.pose_move_s, 0.2, 60.0);
  o.finish();
}

void read_teaching(json::Object o, TeachingConfig& t) {
  t.hand_stiffness = o.number("hand_stiffness", t.hand_stiffness, 1.0, 1e4);
  t.hand_damping = o.number("hand_damping", t.hand_damping, 0.0, 1e3);
  t.max_force_n = o.number("max_force_n", t.max_force_n, 1.0, 200.0);
  t.goal_speed = o.number("goal_speed", t.goal_speed, 1e-3, 1.0);
  range(o, "stroke_min_s", "stroke_max_s", t.stroke_min_s, t.stroke_max_s, 0.1, 60.0);
  range(o, "pause_min_s", "pause_max_s", t.pause_min_s, t.pause_max_s, 0.0, 60.0);
  t.admittance_inertia = o.number("admittance_inertia", t.admittance_inertia, 1e-3, 100.0);
  t.admittance_damping = o.number("admittance_damping", t.admittance_damping, 0.0, 1e3);
  t.dead_band_nm = o.number("dead_band_nm", t.dead_band_nm, 0.0, 50.0);
  o.finish();
}

// The scenario the keys of a file start from, for the robot `robot` read from `robot_file`.
Scenario scenario_for(const std::string& robot_file, const RobotDescription& robot) {
  const int n = static_cast<int>(robot.chain.joints.size());
  if (n < 1)
    throw Error::at(robot_file, 0, "joints",
                    "the twin simulates arms of 1 or more revolute joints; this robot has none");
  Scenario s;
  s.robot_file = robot_file;
  s.joints = n;
  s.pads_file = robot.pads_file.empty() ? "" : robot.pads_file.lexically_normal().string();
  s.friction_file = robot.friction_file.lexically_normal().string();
  s.initial_q = TwinVector::Zero(n);
  auto& e = s.effects;
  e.ripple.amplitude = TwinVector::Zero(n);
  e.ripple.cycles_per_rev = TwinVector::Constant(n, 12.0);
  e.ripple.phase = TwinVector::Zero(n);
  e.spring.stiffness = TwinVector::Zero(n);
  e.spring.neutral = TwinVector::Zero(n);
  e.coupling.matrix = TwinMatrix::Zero(n, n);
  s.excitation.lower = TwinVector::Constant(n, -std::numbers::pi);
  s.excitation.upper = TwinVector::Constant(n, std::numbers::pi);
  return s;
}

// Refuses an initial pose outside a joint's <limit> (a joint without limits takes any finite
// angle; the reader refuses non-finite numbers).
void require_within_limits(const json::Object& o, const TwinVector& q,
                           const ChainDescription& chain) {
  for (int j = 0; j < q.size(); ++j) {
    const ChainJoint& joint = chain.joints[static_cast<std::size_t>(j)];
    if (q[j] >= joint.lower && q[j] <= joint.upper) continue;
    std::ostringstream m;
    m << q[j] << " rad is outside the limits of joint '" << joint.name << "', [" << joint.lower
      << ", " << joint.upper << "] rad (<limit> in " << chain.source << ")";
    o.fail("initial_q[" + std::to_string(j) + "]", m.str());
  }
}

// The friction file the twin reads: the scenario's or the robot file's; none when the scenario
// turns friction off (the robot file's is then not needed, and one the scenario names is unused).
std::string friction_file(json::Object& o, const Scenario& s) {
  if (s.effects.friction == EffectsConfig::Friction::kNone) return "";
  if (s.friction_file.empty())
    o.fail("friction", "no friction file: name one here or as \"friction\" in " + s.robot_file +
                           ", or set effects.friction to \"none\"");
  return s.friction_file;
}

}  // namespace

std::string to_string(Scenario::Kind kind) {
  switch (kind) {
    case Scenario::Kind::kExcitation:
      return "excitation";
    case Scenario::Kind::kStaticContacts:
      return "static-contacts";
    case Scenario::Kind::kTeaching:
      return "teaching";
  }
  return "excitation";
}

Scenario default_scenario(const std::string& robot_file) {
  return scenario_for(robot_file, load_robot_description(robot_file));
}

Scenario load_scenario(const std::string& path, const std::string& robot_file) {
  json::Object o = json::Object::read_file(path);
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  const std::string robot = robot_file.empty()
                                ? resolve(o, "robot", dir, data_file("arm4.robot.json").string())
                                : robot_file;
  if (!robot_file.empty()) o.text("robot", "");  // replaced: read so that finish() accepts it
  const RobotDescription description = load_robot_description(robot);
  Scenario s = scenario_for(robot, description);
  s.file = path;
  const std::string kind = o.choice("kind", "", {"excitation", "static-contacts", "teaching"});
  s.kind = kind == "excitation"        ? Scenario::Kind::kExcitation
           : kind == "static-contacts" ? Scenario::Kind::kStaticContacts
                                       : Scenario::Kind::kTeaching;
  s.name = o.text("name", kind);
  s.duration_s = o.number("duration_s", s.duration_s, 0.01, 1e6);
  s.inner_rate_hz = o.number("inner_rate_hz", s.inner_rate_hz, 100.0, 1e5);
  s.log_rate_hz = o.number("log_rate_hz", s.log_rate_hz, 1.0, 1e4);
  const double ratio = s.inner_rate_hz / s.log_rate_hz;
  if (std::abs(ratio - std::round(ratio)) > 1e-9 || ratio < 2.0)
    o.fail("log_rate_hz", "inner_rate_hz must be an integer multiple (≥ 2) of log_rate_hz");
  s.pads_file = resolve(o, "pads", dir, s.pads_file);
  s.friction_file = resolve(o, "friction", dir, s.friction_file);
  if (s.kind == Scenario::Kind::kTeaching && s.pads_file.empty())
    o.fail("kind", "teaching needs a robot with skin pads (the hand holds a pad); " + s.robot_file +
                       " names none");
  s.initial_q = vector_of(o, "initial_q", s.initial_q, -kInf, kInf);
  require_within_limits(o, s.initial_q, description.chain);
  read_drive(o.child("drive"), s.drive);
  read_sensors(o.child("sensors"), s.sensors);
  read_pads(o.child("pad_sensors"), s.pads);
  read_effects(o.child("effects"), s.effects);
  s.friction_file = friction_file(o, s);
  read_excitation(o.child("excitation"), s.excitation);
  read_contacts(o.child("contacts"), s.contacts);
  read_teaching(o.child("teaching"), s.teaching);
  o.finish();
  return s;
}

}  // namespace tpf::offline
