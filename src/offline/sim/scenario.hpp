// A digital-twin scenario: which robot, which physical effects, which sensors, which script.
// Loaded from a JSON file in data/scenarios/; every key is optional except "kind", unknown keys
// and impossible values are refused with "file: key.path: reason". docs/twin.md lists the keys.
// Per-joint vectors have one entry per joint of the scenario's robot.
#pragma once

#include <initializer_list>
#include <string>

#include "tpf/common/types.hpp"

namespace tpf::offline {

/// The twin simulates serial revolute arms of any joint count, read from the robot file: its
/// vectors and matrices are sized at run time, and the twin is compiled once for every count.
using TwinVector = Eigen::VectorXd;
using TwinMatrix = Eigen::MatrixXd;

/// A TwinVector from its values: twin_vector({0.0, 0.3, -0.4, 0.0}).
inline TwinVector twin_vector(std::initializer_list<double> values) {
  TwinVector v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values)
    v[i++] = x;
  return v;
}

/// The PH54 drive's cascade: position P → velocity PI → current (limited), gains set from
/// bandwidths and the joint's inertia at the home pose.
struct DriveConfig {
  bool enabled = true;                  ///< false: zero current (passive arm)
  double position_bandwidth_hz = 3.0;   ///< position loop gain Kp = 2π·f  [1/s]
  double velocity_bandwidth_hz = 20.0;  ///< velocity loop Kv = 2π·f·J/K_t  [A/(rad/s)]
  double integral_corner_hz = 3.0;      ///< PI zero: Ki = 2π·f·Kv  [A/rad]
  double velocity_feedforward = 1.0;    ///< share of the reference velocity fed forward
  double current_time_constant = 3e-4;  ///< current loop lag, s
};

/// How the drive and the host report the state (hardware.md §2).
struct SensorConfig {
  double current_noise_ma = 6.0;     ///< white noise on the current reading before 1 mA rounding
  double jitter_probability = 0.02;  ///< a sample taken one inner step (0.5 ms) early or late
  double timestamp_noise_s = 2e-5;   ///< host time-stamp noise
  double drop_probability = 0.002;   ///< a cycle lost: the row is missing, t jumps
};

/// Pneumatic pads (hardware.md §4): p = gain(A)·F_n through a first-order lag, plus drift and
/// noise, sampled at 1 kHz. gain(A) = gain_kpa_per_n·(reference_area/A)^area_exponent.
struct PadSensorConfig {
  double time_constant_s = 0.015;
  double gain_kpa_per_n = 1.5;
  double reference_area_cm2 = 6.0;
  double area_exponent = 0.6;
  double noise_kpa = 0.03;
  double drift_kpa_per_sqrt_s = 0.01;  ///< offset random walk
  double full_scale_kpa = 34.474;      ///< 5 psi
  double adc_step_kpa = 0.0105;        ///< 12-bit ratiometric ADC
};

/// Physical effects. Those marked "undeclared" are not part of the nominal model.
struct EffectsConfig {
  enum class Friction { kNone, kStribeck, kLuGre };
  Friction friction = Friction::kLuGre;  ///< memory (LuGre) or memoryless smooth Stribeck
  bool load_dependent_friction = true;   ///< α_c, α_v of the friction file
  bool gravity = true;
  struct Ripple {  ///< undeclared: τ = A·sin(n·q + φ), position-periodic (gear meshing)
    bool enabled = false;
    TwinVector amplitude;       ///< N·m, default 0
    TwinVector cycles_per_rev;  ///< default 12
    TwinVector phase;           ///< rad, default 0
  } ripple;
  struct Payload {  ///< undeclared: point mass on the last link
    bool enabled = false;
    double mass = 0.0;                                   ///< kg
    Vector3<double> position = Vector3<double>::Zero();  ///< in the last link's frame, m
  } payload;
  struct Thermal {  ///< temperature always simulated (temp<j>); drift of b only when enabled
    bool enabled = false;
    double ambient_c = 25.0;
    double initial_c = 28.0;
    double heating_k_per_a2s = 0.02;  ///< dT/dt = k·i² − (T − T_amb)/τ
    double time_constant_s = 600.0;
    double viscous_per_k = -0.012;  ///< b(T) = b·(1 + β(T − T_initial))
  } thermal;
  struct Spring {  ///< undeclared: τ = −k·(q − q0) (cable, spring)
    bool enabled = false;
    TwinVector stiffness;  ///< N·m/rad, default 0
    TwinVector neutral;    ///< rad, default 0
  } spring;
  struct Delay {  ///< undeclared: motor torque lags the reported current
    bool enabled = false;
    double delay_s = 0.0;
  } delay;
  struct Coupling {  ///< undeclared: τ_applied = (I + C)·K_t·i
    bool enabled = false;
    TwinMatrix matrix;  ///< N×N, default 0
  } coupling;
};

/// Contact-free excitation: each joint alternates rests and minimum-jerk moves of random size
/// and speed in both directions, independently of the others.
struct ExcitationConfig {
  double rest_min_s = 0.4, rest_max_s = 2.5;
  double move_min_rad = 0.05, move_max_rad = 1.0;
  double speed_min = 0.05, speed_max = 0.8;  ///< peak speed, rad/s
  /// The range every script moves in (excitation moves, contact poses, teaching goals), rad,
  /// intersected with the joint limits; default ±π.
  TwinVector lower, upper;
};

/// Static contacts: the arm holds a pose while a hand pushes on one pad (normal + shear).
struct ContactConfig {
  double force_min_n = 3.0, force_max_n = 20.0;
  double shear_ratio_max = 0.5;  ///< |shear| / normal
  double area_min_cm2 = 2.0, area_max_cm2 = 12.0;
  double ramp_s = 0.25;
  double hold_min_s = 1.0, hold_max_s = 3.0;
  double pause_min_s = 0.8, pause_max_s = 2.0;
  int pushes_per_pose = 4;
  double pose_move_s = 2.5;  ///< duration of the min-jerk move to the next pose
};

/// Kinesthetic teaching: a hand holds a pad and drags it towards goal points (a spring–damper
/// human model); the arm follows under joint-space admittance on the estimated external torque.
struct TeachingConfig {
  double hand_stiffness = 150.0;  ///< N/m
  double hand_damping = 25.0;     ///< N·s/m
  double max_force_n = 25.0;
  double goal_speed = 0.06;  ///< m/s, speed of the moving goal
  double stroke_min_s = 2.0, stroke_max_s = 5.0;
  double pause_min_s = 1.0, pause_max_s = 2.5;
  double admittance_inertia = 0.6;  ///< kg·m² per joint
  double admittance_damping = 6.0;  ///< N·m·s/rad per joint
  double dead_band_nm = 0.8;        ///< |τ̂_ext| below this is ignored
};

struct Scenario {
  enum class Kind { kExcitation, kStaticContacts, kTeaching };
  std::string file;  ///< where it was loaded from ("" when built in code)
  std::string name;
  Kind kind = Kind::kExcitation;
  double duration_s = 600.0;
  double inner_rate_hz = 2000.0;
  double log_rate_hz = 400.0;
  std::string robot_file;     ///< default data/arm4.robot.json
  int joints = 0;             ///< of the robot file, at least 1
  std::string pads_file;      ///< default: the robot file's "pads"; "" = no skin, no pad sensors
  std::string friction_file;  ///< default: the robot file's "friction"; "" = effects.friction none
  TwinVector initial_q;       ///< rad, default 0
  DriveConfig drive;
  SensorConfig sensors;
  PadSensorConfig pads;
  EffectsConfig effects;
  ExcitationConfig excitation;
  ContactConfig contacts;
  TeachingConfig teaching;
};

/// The scenario the keys of a file start from, for `robot_file`: every per-joint vector sized
/// for its joint count at its default, pads and friction from the robot file. Throws tpf::Error
/// naming the robot file when it has no joint.
Scenario default_scenario(const std::string& robot_file);

/// Reads a scenario file. Relative robot/pads/friction paths resolve against the scenario's
/// folder. `robot_file`, when not empty, replaces the file's "robot" (tpf simulate --robot).
/// Throws tpf::Error "file: key.path: reason" on an unknown key, an impossible value, a
/// per-joint vector whose length is not the robot's joint count, an initial_q outside a joint's
/// <limit>, or no friction file (scenario or robot file) unless effects.friction is "none": then
/// no friction file is read and friction_file is "" (one the scenario names goes unused).
Scenario load_scenario(const std::string& path, const std::string& robot_file = "");

/// The scenario kind as written in files: "excitation", "static-contacts", "teaching".
std::string to_string(Scenario::Kind kind);

}  // namespace tpf::offline
