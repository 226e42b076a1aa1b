#include "planar_arm_generator.hpp"

#include <cmath>
#include <random>
#include <vector>

namespace tpf::test {
namespace {

// ds/dt of the motion's progress: 1 while moving, 0 during a stop, raised-cosine ramps between.
struct StopGate {
  struct Stop {
    double begin, end;  // the gate is 0 on [begin + ramp, end], ramps on either side
  };
  std::vector<Stop> stops;
  double ramp = 0.25;

  StopGate(std::mt19937_64& rng, double duration, bool enabled) {
    if (!enabled) return;
    std::uniform_real_distribution<double> moving(3.0, 7.0), still(0.5, 2.0);
    for (double t = moving(rng); t < duration; t += moving(rng)) {
      const double length = still(rng);
      stops.push_back({t, t + ramp + length});
      t += 2 * ramp + length;
    }
  }
  // Gate value and its time derivative at t.
  std::pair<double, double> operator()(double t) const {
    for (const Stop& s : stops) {
      if (t < s.begin) break;
      if (t < s.begin + ramp) {
        const double a = M_PI * (t - s.begin) / ramp;
        return {0.5 * (1 + std::cos(a)), -0.5 * M_PI / ramp * std::sin(a)};
      }
      if (t < s.end) return {0.0, 0.0};
      if (t < s.end + ramp) {
        const double a = M_PI * (t - s.end) / ramp;
        return {0.5 * (1 - std::cos(a)), 0.5 * M_PI / ramp * std::sin(a)};
      }
    }
    return {1.0, 0.0};
  }
};

// One joint's path of the progress s: centre + amplitude·(0.65 sin(w1 s + p1) + 0.35 sin(w2 s +
// p2)).
struct JointPath {
  double centre, amplitude, w1, w2, p1, p2;
  double at(double s) const {
    return centre + amplitude * (0.65 * std::sin(w1 * s + p1) + 0.35 * std::sin(w2 * s + p2));
  }
  double d1(double s) const {
    return amplitude * (0.65 * w1 * std::cos(w1 * s + p1) + 0.35 * w2 * std::cos(w2 * s + p2));
  }
  double d2(double s) const {
    return -amplitude *
           (0.65 * w1 * w1 * std::sin(w1 * s + p1) + 0.35 * w2 * w2 * std::sin(w2 * s + p2));
  }
};

double quantise(double value, double quantum) {
  return quantum > 0 ? quantum * std::round(value / quantum) : value;
}

// The forearm with the payload as one body: mass, first moment h about the elbow at the angle ψ
// from the link's x axis (a point (x, 0, z) of the link at absolute angle a sits at
// r·(cos(a + ψ), −sin(a + ψ)) in the plane, ψ = atan2(−z, x)), and inertia about the elbow axis.
struct Forearm {
  double mass, h, psi, inertia;
};

Forearm forearm(const PlanarArm& arm) {
  const double hx = arm.m2 * arm.c2 + arm.payload_mass * arm.payload_com[0];
  const double hz = arm.payload_mass * arm.payload_com[1];
  return {arm.m2 + arm.payload_mass, std::hypot(hx, hz), std::atan2(-hz, hx),
          arm.I2 + arm.m2 * arm.c2 * arm.c2 + arm.payload_mass * arm.payload_com.squaredNorm()};
}

}  // namespace

Eigen::Vector2d PlanarArm::gravity(const Eigen::Vector2d& q) const {
  // Axes along y, gravity along −z: a point r along a link at absolute angle a sits at height
  // −r·sin(a); G = ∂V/∂q with V = Σ m g z.
  const Forearm f = forearm(*this);
  const double a1 = q[0], a2 = q[0] + q[1] + f.psi;
  const double g2 = -g * f.h * std::cos(a2);
  return {-g * (m1 * c1 + f.mass * L1) * std::cos(a1) + g2, g2};
}

Eigen::Vector2d PlanarArm::inverse_dynamics(const Eigen::Vector2d& q, const Eigen::Vector2d& dq,
                                            const Eigen::Vector2d& ddq) const {
  const Forearm f = forearm(*this);
  const double c = std::cos(q[1] + f.psi), s = std::sin(q[1] + f.psi);
  // Armature Cᵀ·diag(I_a)·C with C = [1 0; k 1]: motor 2 turns with q̇₂ + k·q̇₁.
  const double k = motor2_coupling;
  const double m11 =
      I1 + m1 * c1 * c1 + f.inertia + f.mass * L1 * L1 + 2 * L1 * f.h * c + armature * (1 + k * k);
  const double m12 = f.inertia + L1 * f.h * c + k * armature;
  const double m22 = f.inertia + armature;
  const double h = L1 * f.h * s;
  Eigen::Vector2d tau;
  tau[0] = m11 * ddq[0] + m12 * ddq[1] - h * (2 * dq[0] * dq[1] + dq[1] * dq[1]);
  tau[1] = m12 * ddq[0] + m22 * ddq[1] + h * dq[0] * dq[0];
  return tau + gravity(q);
}

std::string planar_robot_file() {
  return std::string(TPF_TEST_SOURCE_DIR) + "/planar2/planar2.robot.json";
}

std::string planar_coupled_robot_file() {
  return std::string(TPF_TEST_SOURCE_DIR) + "/planar2/planar2_coupled.robot.json";
}

offline::Log generate_planar_log(const PlanarArmPlant& p) {
  std::mt19937_64 rng(p.seed);
  std::uniform_real_distribution<double> frequency(0.5, 1.3), phase(0.0, 2 * M_PI);
  std::normal_distribution<double> unit(0.0, 1.0);
  PlanarArm arm;
  arm.payload_mass = p.payload_mass;
  arm.payload_com = p.payload_com;
  arm.motor2_coupling = p.motor2_coupling;
  const double dt = 1.0 / p.rate_hz;
  const int lag = static_cast<int>(std::lround(p.delay_s * p.rate_hz));
  const int n = static_cast<int>(p.duration_s * p.rate_hz);
  const int total = n + lag;
  const StopGate gate(rng, total * dt, p.random_stops);
  JointPath path[2];
  for (int j = 0; j < 2; ++j)
    path[j] = {p.centre[j], p.amplitude[j], frequency(rng), frequency(rng), phase(rng), phase(rng)};

  std::vector<Eigen::Vector2d> q(total), dq(total), tau(total), temperature(total);
  Eigen::Vector2d bristle = Eigen::Vector2d::Zero();  // Dahl deflection, rad
  double progress = 0.0;
  for (int k = 0; k < total; ++k) {
    const double t = k * dt;
    if (k > 0) {  // trapezoid in 20 sub-steps: s(t) = ∫ gate
      constexpr int kSub = 20;
      for (int i = 0; i < kSub; ++i) {
        const double a = t - dt + i * dt / kSub;
        progress += 0.5 * (gate(a).first + gate(a + dt / kSub).first) * dt / kSub;
      }
    }
    const auto [speed, speed_rate] = gate(t);
    Eigen::Vector2d ddq;
    for (int j = 0; j < 2; ++j) {
      q[k][j] = path[j].at(progress);
      dq[k][j] = path[j].d1(progress) * speed;
      ddq[j] = path[j].d2(progress) * speed * speed + path[j].d1(progress) * speed_rate;
    }
    Eigen::Vector2d effort = arm.inverse_dynamics(q[k], dq[k], ddq) + p.coupling_velocity * dq[k] +
                             p.coupling_acceleration * ddq;
    const Eigen::Vector2d load = arm.gravity(q[k]).cwiseAbs();
    temperature[k] = p.temperature_start +
                     p.temperature_rise * (1 - std::exp(-t / p.temperature_time_constant_s));
    for (int j = 0; j < 2; ++j) {
      // Drive j's friction on its motor's velocity (motor 2: q̇₂ + c·q̇₁), acting through Cᵀ.
      const double v = j == 1 ? dq[k][1] + p.motor2_coupling * dq[k][0] : dq[k][j];
      double level = v >= 0 ? p.coulomb_positive[j] : p.coulomb_negative[j];
      level += p.own_load[j] * load[j];
      if (j == 0) level += p.neighbour_load * load[1];
      const double viscous = (p.viscous[j] + (v >= 0 ? 1 : -1) * p.viscous_asymmetry[j]) *
                             (1 + p.thermal_viscous[j] * (temperature[k][j] - 25.0));
      if (v != 0.0) {  // exact step of ż = v − σ0|v|z/level at constant v
        const double steady = (v > 0 ? 1.0 : -1.0) * level / p.bristle_stiffness[j];
        bristle[j] = steady + (bristle[j] - steady) *
                                  std::exp(-p.bristle_stiffness[j] * std::abs(v) * dt / level);
      }
      const double motor_friction = p.bristle_stiffness[j] * bristle[j] + viscous * v;
      if (j == 1 && p.motor2_coupling != 0.0) effort[0] += p.motor2_coupling * motor_friction;
      effort[j] += motor_friction + p.offset[j] +
                   p.spring_stiffness[j] * (q[k][j] - p.spring_neutral[j]) +
                   p.ripple_amplitude[j] * std::sin(p.ripple_cycles[j] * q[k][j]) +
                   p.motor_ripple_amplitude[j] *
                       std::sin(p.motor_ripple_cycles[j] * arm.gear_ratio * q[k][j] + 0.7);
    }
    tau[k] = effort;
  }

  std::mt19937_64 own_noise(p.noise_seed);
  std::mt19937_64& noise = p.noise_seed ? own_noise : rng;
  offline::Log log;
  log.source = "planar2-generator-seed" + std::to_string(p.seed);
  log.meta.set("source", "independent test generator (tests/generator), not the twin");
  log.columns = {"t", "q1", "q2", "dq1", "dq2", "tau1", "tau2"};
  if (p.log_temperature) log.columns.insert(log.columns.end(), {"temp1", "temp2"});
  log.values.resize(n, static_cast<Eigen::Index>(log.columns.size()));
  for (int k = 0; k < n; ++k) {
    const int motion = k + lag;  // the effort logged now is the one of `lag` samples ago
    log.values(k, 0) = k * dt;
    for (int j = 0; j < 2; ++j) {
      log.values(k, 1 + j) = quantise(q[motion][j], p.position_quantum);
      log.values(k, 3 + j) =
          quantise(dq[motion][j] + p.velocity_noise * unit(noise), p.velocity_quantum);
      log.values(k, 5 + j) = quantise(tau[k][j] + p.effort_noise * unit(noise), p.effort_quantum);
      if (p.log_temperature) log.values(k, 7 + j) = quantise(temperature[motion][j], 0.1);
    }
  }
  return log;
}

}  // namespace tpf::test
