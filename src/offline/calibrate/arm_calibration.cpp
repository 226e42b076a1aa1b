#include "offline/calibrate/arm_calibration.hpp"

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
  setup.parameters.compensator_speed_limit = speed_envelope(samples);
  setup.parameters.compensator_acceleration_limit = acceleration_envelope(setup, samples);
  const TransitionSigma<double, kArmJoints> sigma = calibrate_arm_sigma(setup, samples, log.source);
  setup.parameters.torque_alarm_samples = calibrate_torque_alarm(setup, log);
  return sigma;
}

}  // namespace tpf::offline
