// Short, seeded digital-twin logs turned into estimator samples, and the twin's nominal model.
// Everything here is simulated.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "offline/log/log.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "support/arm_fixture.hpp"
#include "tpf/estimation/estimator.hpp"
#include "tpf/friction/friction_file.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::test {

inline constexpr int kPads = 11;
using ArmSample = EstimatorSample<double, kJoints, kPads>;
using TwinEstimator = Estimator<double, kJoints, kPads>;
/// Current noise of the twin's drives (sensors.current_noise_ma) with 1 mA rounding.
inline constexpr double kCurrentNoiseMa = 6.0;

/// A fixed-size sample as one of run-time joint count (and pad count too when P is
/// Eigen::Dynamic): what the offline replay hands an estimator loaded at Eigen::Dynamic.
template <int P>
EstimatorSample<double, Eigen::Dynamic, P> any_count_sample(const ArmSample& s) {
  EstimatorSample<double, Eigen::Dynamic, P> a;
  a.resize(kJoints, kPads);
  a.t = s.t;
  a.q = s.q;
  a.dq = s.dq;
  a.effort = s.effort;
  a.pressure = s.pressure;
  a.ddq = s.ddq;
  a.has_ddq = s.has_ddq;
  return a;
}

/// The simulated log of data/scenarios/<scenario>.json, cached per (scenario, seed, duration).
inline const offline::Log& twin_log(const std::string& scenario, unsigned seed, double duration) {
  static std::map<std::tuple<std::string, unsigned, double>, offline::Log> cache;
  const auto key = std::make_tuple(scenario, seed, duration);
  auto it = cache.find(key);
  if (it == cache.end()) {
    const offline::Scenario s =
        offline::load_scenario(data_path("scenarios/" + scenario + ".json"));
    it = cache.emplace(key, offline::simulate_to_log(s, seed, duration)).first;
  }
  return it->second;
}

/// Rows of a log as estimator samples of the fixed-size twin estimator (estimator_samples: effort
/// = i<j> in mA converted to N·m with the arm's K_t, no q̈: the estimator derives it).
inline std::vector<ArmSample> samples_from_log(const offline::Log& log) {
  const auto rows = offline::estimator_samples(log, joint_count_cast<Eigen::Dynamic>(arm()), kPads);
  std::vector<ArmSample> samples(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    samples[r].t = rows[r].t;
    samples[r].q = rows[r].q;
    samples[r].dq = rows[r].dq;
    samples[r].effort = rows[r].effort;
    samples[r].pressure = rows[r].pressure;
  }
  return samples;
}

/// Rows of the short static-contacts log (seed 5, 7 s) most estimator tests run: 6 s.
inline constexpr std::size_t kStaticContactRows = 2400;

/// That log as estimator samples (computed once per program).
inline const std::vector<ArmSample>& static_contact_samples() {
  static const std::vector<ArmSample> s = samples_from_log(twin_log("static-contacts", 5, 7));
  return s;
}

/// The twin's nominal model (N·m): the true rigid body and the memoryless Stribeck curve of
/// data/arm4.friction.json (the twin adds LuGre memory on top).
inline NominalModel<double, kJoints> twin_nominal() {
  return nominal_from_model<kJoints>(
      arm(), load_stribeck_parameters<double, kJoints>(data_path("arm4.friction.json")));
}

inline std::vector<Pad> twin_pads() {
  return load_pads(data_path("arm4.pads.json"), arm());
}

/// Per joint mA per N·m of the twin (1000/K_t): the tests state currents in mA, as the drive
/// reports them, and the estimator computes in N·m.
inline Vec milliamperes_per_newton_metre() {
  return current_from_torque(arm(), Vec::Ones().eval());
}

/// Parameters for the twin: pad gain for the twin's 1.5 kPa/N on a 25 cm² pad, static dead band
/// from the current noise (in N·m).
inline EstimatorParameters<double, kJoints> twin_parameters() {
  EstimatorParameters<double, kJoints> p;
  p.skin.force_gain = 1.0 / (1.5 * 1000.0 * 0.0025);
  const double noise = std::sqrt(kCurrentNoiseMa * kCurrentNoiseMa + 1.0 / 12.0);
  p.static_dead_band = static_dead_band_from_noise<double, kJoints>(
      Vec::Constant(noise).cwiseQuotient(milliamperes_per_newton_metre()), 5);
  return p;
}

}  // namespace tpf::test
