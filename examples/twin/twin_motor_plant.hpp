// The digital twin behind the emulated PH54 chain: tpf::offline's rigid-body arm with LuGre
// friction (TwinPlant) and the PH54 drive cascade (Ph54Drive), advanced at the scenario's inner
// rate, with the scenario's hand pushing on the pads (static-contacts script) and the pads'
// pressures (PadSensors) for the emulated pad board. Everything it produces is simulated.
//
// Until the host first switches torque on, the arm rests at the scenario's initial pose (on its
// stand or held, as a real arm is before power-up: a start-up that turns torque off does not
// drop it). From then on, per motor, from the control table the host wrote (MotorGoal):
//   torque off     i = 0: the arm moves under gravity and friction; joints stop at their limits;
//   position mode  i = Ph54Drive(q_goal, q̇_ref = 0, q, q̇): position P → velocity PI → current lag;
//   velocity mode  i = Ph54Drive(q, q̇_goal, q, q̇) (no position error, velocity PI only);
//   current mode   τ_i·di/dt = clamp(i_goal, ±i_max) − i.
// Then M(q)q̈ + C q̇ + G = K_t·i + τ_ext − τ_fric with τ_ext = J_v(q)ᵀ·F of the scripted push.
// The reported current is i plus the twin's white current noise (SensorConfig::current_noise_ma).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "dynamixel/emulator/motor_plant.hpp"
#include "offline/sim/contact_script.hpp"
#include "offline/sim/scenario.hpp"

namespace tpf::dxl::emu {

struct TwinMotorPlantOptions {
  std::uint64_t seed = 1;
  /// Ground-truth samples kept, one per inner step (2 kHz); 0 keeps none. Reserved up front.
  std::size_t truth_capacity = 0;
};

/// The twin's truth at one inner step (what a log's gt_* columns hold).
struct TwinTruth {
  double t = 0.0;               ///< s of simulated time since the plant was built
  offline::TwinVector q;        ///< rad
  offline::TwinVector tau_ext;  ///< N·m, environment on the robot
  int pad = -1;                 ///< pad pushed (0-based), −1: none
  double normal_force_n = 0.0;  ///< push into that pad, N
};

class TwinMotorPlant final : public MotorPlant {
 public:
  /// Builds the twin of `scenario` (robot, pads, friction, effects, drive and sensor settings).
  /// A static-contacts scenario's pushes (make_static_contact_plan, seeded) act on the pads
  /// whatever pose the host holds; its pose schedule is not used (the host commands the motors).
  /// Start-up code: throws tpf::Error on bad files.
  explicit TwinMotorPlant(const offline::Scenario& scenario, TwinMotorPlantOptions options = {});
  ~TwinMotorPlant() override;

  /// Replaces the pushes (times in simulated seconds since the plant was built).
  void set_contacts(offline::ContactScript contacts);

  std::size_t joints() const override { return state_.size(); }
  /// Advances by dt in inner steps of 1/inner_rate_hz (the remainder carries over).
  void step(double dt, std::span<const MotorGoal> goals) override;
  MotorState state(std::size_t k) const override { return state_[k]; }

  /// Number of pads of the layout.
  int pad_count() const;
  /// Copies the latest pad readings (kPa gauge, 1 kHz) into kpa[0..pad_count()); returns the
  /// count copied. Thread-safe against step().
  int pad_pressures(std::span<float> kpa) const;
  /// Simulated time [s].
  double time() const noexcept { return t_; }
  /// The kept ground truth (read it after the emulator thread stopped).
  const std::vector<TwinTruth>& truth() const noexcept { return truth_; }

 private:
  void inner_step(std::span<const MotorGoal> goals);
  void motor_current(std::span<const MotorGoal> goals);
  void stop_at_limits();

  struct Twin;  // the offline simulator's parts
  std::unique_ptr<Twin> twin_;
  TwinMotorPlantOptions options_;
  double h_ = 0.0, t_ = 0.0, pending_ = 0.0;
  long steps_ = 0, pad_every_ = 1;
  bool powered_ = false;           ///< the host has switched torque on at least once
  std::vector<bool> was_enabled_;  ///< per joint
  std::vector<MotorState> state_;  ///< per joint
  std::vector<TwinTruth> truth_;
  mutable std::mutex pads_mutex_;
  std::vector<float> pad_kpa_;
};

}  // namespace tpf::dxl::emu
