// An independent log generator for testing diagnosis on data the twin did not make: a two-link
// planar arm in a vertical plane (planar2/), its closed-form Lagrangian dynamics written here
// (not tpf's RNEA, not src/offline/sim), a prescribed motion with random stops, friction with
// memory (a Dahl bristle per joint with direction-dependent levels), planted effects, noise and
// quantisation. Writes a tpf Log in memory (t, q<j>, dq<j>, tau<j> in N·m, and temp<j> in °C when
// asked; no ddq: the tools derive it).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "offline/log/log.hpp"

namespace tpf::test {

/// What the generator plants. Every effect is off (zero) by default.
struct PlanarArmPlant {
  std::uint64_t seed = 1;
  /// 0: the noise continues the motion's random stream; else its own stream, so that two plants
  /// of one seed and different noise seeds repeat one motion with independent noise.
  std::uint64_t noise_seed = 0;
  double duration_s = 60.0;
  double rate_hz = 100.0;
  Eigen::Vector2d centre{0.3, 0.5};     ///< rad, middle of each joint's motion
  Eigen::Vector2d amplitude{1.2, 1.4};  ///< rad, half the range of motion
  bool random_stops = true;             ///< the motion pauses 0.5–2 s every few seconds
  /// c: motor 2 turns with r·(q₂ + c·q₁) (a coupled wrist, planar2_coupled.robot.json has
  /// c = 0.5); its friction (index 1 of the friction fields, on the motor's velocity q̇₂ + c·q̇₁)
  /// and armature act through C = [1 0; c 1]: τ_joint = Cᵀ·τ_motor. 0: uncoupled.
  double motor2_coupling = 0.0;

  // Friction (Dahl bristle with a direction-dependent sliding level; memory at reversals/rests).
  Eigen::Vector2d coulomb_positive{0.40, 0.25};  ///< N·m, sliding level for q̇ > 0
  Eigen::Vector2d coulomb_negative{0.40, 0.25};  ///< N·m, for q̇ < 0
  Eigen::Vector2d viscous{0.30, 0.20};           ///< N·m·s/rad
  Eigen::Vector2d viscous_asymmetry{0, 0};  ///< a: viscous + a for q̇ > 0, viscous − a for q̇ < 0
  Eigen::Vector2d bristle_stiffness{400, 300};  ///< N·m/rad
  double neighbour_load = 0.0;     ///< joint 1's sliding level grows by this × |G_2(q)| [1]
  Eigen::Vector2d own_load{0, 0};  ///< joint j's sliding level grows by this × |G_j(q)| [1]

  // Temperature: T_j(t) = start + rise·(1 − exp(−t/τ)), logged as temp<j> (0.1 K quantum) when
  // log_temperature; the viscous coefficient is b_j·(1 + thermal_viscous_j·(T_j − 25 °C)).
  bool log_temperature = false;
  Eigen::Vector2d temperature_start{30, 32};  ///< °C
  Eigen::Vector2d temperature_rise{12, 9};    ///< K
  double temperature_time_constant_s = 40.0;
  Eigen::Vector2d thermal_viscous{0, 0};  ///< relative change of b_j per K [1/K]

  // Planted effects.
  Eigen::Vector2d offset{0, 0};            ///< N·m, constant
  Eigen::Vector2d spring_stiffness{0, 0};  ///< N·m/rad, τ += k (q − q0)
  Eigen::Vector2d spring_neutral{0, 0};    ///< q0, rad
  Eigen::Vector2d ripple_amplitude{0, 0};  ///< N·m, τ += a·sin(n q)
  Eigen::Vector2d ripple_cycles{8, 8};     ///< n, periods per revolution
  /// N·m, τ += a·sin(n·r·q + 0.7): ripple of the motor angle (r = gear ratio of the robot file).
  Eigen::Vector2d motor_ripple_amplitude{0, 0};
  Eigen::Vector2d motor_ripple_cycles{2, 2};  ///< n, periods per motor revolution
  /// τ_j += C_v(j, k)·q̇_k + C_a(j, k)·q̈_k (zero diagonal): motion coupling between the drives.
  Eigen::Matrix2d coupling_velocity = Eigen::Matrix2d::Zero();      ///< N·m·s/rad
  Eigen::Matrix2d coupling_acceleration = Eigen::Matrix2d::Zero();  ///< N·m·s²/rad
  // A payload on the last link, not in the robot file: a point mass at (x, 0, z) of its frame.
  double payload_mass = 0.0;              ///< kg
  Eigen::Vector2d payload_com{0.0, 0.0};  ///< (x, z), m
  double delay_s = 0.0;                   ///< the logged effort lags the motion on every joint

  // Sensors.
  double effort_noise = 0.02;        ///< N·m, std
  double effort_quantum = 0.005;     ///< N·m
  double velocity_noise = 0.0006;    ///< rad/s, std
  double velocity_quantum = 0.004;   ///< rad/s (a stopped joint reads exactly 0)
  double position_quantum = 3.8e-4;  ///< rad (14-bit encoder on the output)
};

/// The generator's arm (must match planar2/planar2.urdf and planar2.robot.json), plus a payload
/// point mass on the forearm that the robot file does not hold.
struct PlanarArm {
  double m1 = 2.0, c1 = 0.2, L1 = 0.4, I1 = 0.03;
  double m2 = 1.2, c2 = 0.15, I2 = 0.012;
  double gear_ratio = 100;
  double armature = 1e-5 * gear_ratio * gear_ratio;  ///< rotor inertia × gear ratio², kg·m²
  double g = 9.81;
  double payload_mass = 0.0;              ///< kg
  Eigen::Vector2d payload_com{0.0, 0.0};  ///< (x, z) in the forearm's frame, m
  double motor2_coupling = 0.0;  ///< c of PlanarArmPlant: motor 2's armature on q̈₂ + c·q̈₁

  /// Rigid-body torque (incl. armature) the drives must produce, closed form.
  Eigen::Vector2d inverse_dynamics(const Eigen::Vector2d& q, const Eigen::Vector2d& dq,
                                   const Eigen::Vector2d& ddq) const;
  /// Gravity torque G(q) the drives must produce to hold the arm.
  Eigen::Vector2d gravity(const Eigen::Vector2d& q) const;
};

/// Path of planar2.robot.json.
std::string planar_robot_file();
/// Path of planar2_coupled.robot.json (motor 2 coupled_to joint1 with c = 0.5).
std::string planar_coupled_robot_file();

/// Generates the log of `plant`.
offline::Log generate_planar_log(const PlanarArmPlant& plant);

}  // namespace tpf::test
