#include "offline/calibrate/estimator_calibration.hpp"

#include <limits>

#include "offline/calibrate/torque_alarm.hpp"
#include "offline/replay/estimator_samples.hpp"
#include "tpf/common/joint_counts.hpp"

namespace tpf::offline {

template <int N>
EstimatorParameters<double, N> calibrate_estimator(EstimatorSetup<N> setup, const Log& log,
                                                   double pad_gain_kpa_per_n) {
  setup.parameters = estimator_parameters_from_noise<N>(
      estimate_sensor_noise(log, setup.nominal.model.torque_constant), pad_gain_kpa_per_n);
  calibrate_with_compensator(setup, log);
  return setup.parameters;
}

template <int N>
TransitionSigma<double, N> calibrate_with_compensator(EstimatorSetup<N>& setup, const Log& log) {
  const auto samples =
      estimator_samples<N>(log, setup.nominal.model, static_cast<int>(setup.pads.size()));
  EstimatorParameters<double, N>& p = setup.parameters;
  p.compensator_speed_limit = speed_envelope(samples);
  // The acceleration limit is this log's own envelope, read off the pass below: no row of the log
  // lies beyond it, so the passes run as if it were already set.
  p.compensator_acceleration_limit.setConstant(std::numeric_limits<double>::infinity());
  const TransitionSigma<double, N> sigma = calibrate_sigma(setup, samples, log.source);
  const EstimatorTrace with_bands = replay_estimator(setup, samples);
  p.compensator_acceleration_limit = acceleration_envelope<N>(with_bands);
  p.torque_alarm_samples = calibrate_torque_alarm(with_bands);
  return sigma;
}

#define TPF_INSTANTIATE_CALIBRATION(N)                                                          \
  template EstimatorParameters<double, N> calibrate_estimator<N>(EstimatorSetup<N>, const Log&, \
                                                                 double);                       \
  template TransitionSigma<double, N> calibrate_with_compensator<N>(EstimatorSetup<N>&, const Log&);
TPF_FOR_EACH_JOINT_COUNT(TPF_INSTANTIATE_CALIBRATION)
#undef TPF_INSTANTIATE_CALIBRATION

}  // namespace tpf::offline
