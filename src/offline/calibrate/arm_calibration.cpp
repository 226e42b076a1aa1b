#include "offline/calibrate/arm_calibration.hpp"

#include <limits>

#include "offline/calibrate/torque_alarm.hpp"
#include "offline/training/estimator_samples.hpp"

namespace tpf::offline {

ArmParameters calibrate_arm_estimator(ArmEstimatorSetup setup, const Log& log,
                                      double pad_gain_kpa_per_n) {
  setup.parameters = arm_estimator_parameters(estimate_sensor_noise(log), pad_gain_kpa_per_n);
  calibrate_with_compensator(setup, log);
  return setup.parameters;
}

TransitionSigma<double, kArmJoints> calibrate_with_compensator(ArmEstimatorSetup& setup,
                                                               const Log& log) {
  const std::vector<ArmSample> samples = estimator_samples<kArmJoints, kArmPads>(log);
  ArmParameters& p = setup.parameters;
  p.compensator_speed_limit = speed_envelope(samples);
  // The acceleration limit is this log's own envelope, read off the pass below: no row of the log
  // lies beyond it, so the passes run as if it were already set.
  p.compensator_acceleration_limit.setConstant(std::numeric_limits<double>::infinity());
  const TransitionSigma<double, kArmJoints> sigma = calibrate_arm_sigma(setup, samples, log.source);
  const EstimatorTrace with_bands = trace_arm_estimator(setup, samples);
  p.compensator_acceleration_limit = acceleration_envelope(with_bands);
  p.torque_alarm_samples = calibrate_torque_alarm(with_bands);
  return sigma;
}

}  // namespace tpf::offline
