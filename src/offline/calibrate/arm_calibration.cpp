#include "offline/calibrate/arm_calibration.hpp"

#include "offline/evaluate/evaluation.hpp"
#include "offline/training/estimator_samples.hpp"

namespace tpf::offline {

ArmParameters calibrate_arm_estimator(ArmEstimatorSetup setup, const Log& log,
                                      double pad_gain_kpa_per_n) {
  setup.parameters = arm_estimator_parameters(estimate_sensor_noise(log), pad_gain_kpa_per_n);
  calibrate_arm_sigma(setup, estimator_samples<kArmJoints, kArmPads>(log), log.source);
  setup.parameters.torque_alarm_samples = calibrate_torque_alarm(setup, log);
  return setup.parameters;
}

}  // namespace tpf::offline
