#include "offline/calibrate/estimator_calibration.hpp"

#include <limits>

#include "offline/calibrate/torque_alarm.hpp"
#include "offline/replay/estimator_samples.hpp"

namespace tpf::offline {

ReplayParameters calibrate_estimator(ReplaySetup setup, const Log& log, double pad_gain_kpa_per_n) {
  setup.parameters = estimator_parameters_from_noise(
      estimate_sensor_noise(log, setup.nominal.model.torque_constant), pad_gain_kpa_per_n);
  calibrate_with_compensator(setup, log);
  return setup.parameters;
}

TransitionSigma<double, Eigen::Dynamic> calibrate_with_compensator(ReplaySetup& setup,
                                                                   const Log& log) {
  const auto samples =
      estimator_samples(log, setup.nominal.model, static_cast<int>(setup.pads.size()));
  ReplayParameters& p = setup.parameters;
  p.compensator_speed_limit = speed_envelope(samples);
  // The acceleration limit is this log's own envelope, read off the pass below: no row of the log
  // lies beyond it, so the passes run as if it were already set.
  p.compensator_acceleration_limit.setConstant(std::numeric_limits<double>::infinity());
  const TransitionSigma<double, Eigen::Dynamic> sigma = calibrate_sigma(setup, samples, log.source);
  const EstimatorTrace with_bands = replay_estimator(setup, samples);
  p.compensator_acceleration_limit = acceleration_envelope(with_bands);
  p.torque_alarm_samples = calibrate_torque_alarm(with_bands);
  return sigma;
}

}  // namespace tpf::offline
