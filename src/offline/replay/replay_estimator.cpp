#include "offline/replay/replay_estimator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tpf/common/joint_counts.hpp"
#include "tpf/model/effort_unit.hpp"

namespace tpf::offline {
namespace {

/// 1.4826·MAD(x): the std of Gaussian samples, robust to outliers. NaN when x is empty.
double robust_std(std::vector<double>& x) {
  if (x.empty()) return std::nan("");
  const auto mid = x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2);
  std::nth_element(x.begin(), mid, x.end());
  const double median = *mid;
  for (double& v : x)
    v = std::abs(v - median);
  std::nth_element(x.begin(), mid, x.end());
  return 1.4826 * *mid;
}

/// σ of the effort of joint j (1-based) over consecutive static rows.
double effort_noise(const Log& log, const std::string& effort, int j, double period) {
  const Eigen::VectorXd t = log.col("t");
  const auto dq = log.col(indexed_name("dq", j));
  const auto e = log.col(indexed_name(effort, j));
  std::vector<double> d;
  for (Eigen::Index k = 1; k < log.rows(); ++k) {
    const bool rest = std::abs(dq[k]) < 1e-4 && std::abs(dq[k - 1]) < 1e-4;
    if (rest && t[k] - t[k - 1] < 1.5 * period && std::isfinite(e[k] - e[k - 1]))
      d.push_back(e[k] - e[k - 1]);
  }
  if (d.size() < 10)
    throw Error::at(log.source, 0, indexed_name(effort, j),
                    "too few static rows to estimate the effort noise (the joint must rest, "
                    "|dq| < 1e-4 rad/s, for at least 10 consecutive rows)");
  return robust_std(d) / std::sqrt(2.0);
}

/// σ of the raw pad pressure over live readings (off the rails), 0 without pads.
double pad_noise(const Log& log) {
  // A pad whose offset sits at the sensor's rail (0 kPa) reads 0 again and again: its
  // differences there are clipped noise, not noise, and would bias σ low.
  const double full_scale = SkinSettings<double>{}.full_scale_kpa;
  const auto live = [full_scale](double p) { return p > 0.0 && p < full_scale; };
  std::vector<double> d;
  for (int k = 1; k <= log.pad_count(); ++k) {
    const auto p = log.col(indexed_name("p", k));
    for (Eigen::Index r = 1; r < log.rows(); ++r)
      if (live(p[r]) && live(p[r - 1])) d.push_back(p[r] - p[r - 1]);
  }
  return d.empty() ? 0.0 : robust_std(d) / std::sqrt(2.0);
}

}  // namespace

template <int N>
SteppedEstimator<N>::SteppedEstimator(const EstimatorSetup<N>& setup)
    : estimator_(
          std::make_unique<ReplayEstimator<N>>(setup.nominal, setup.pads, setup.parameters)) {
  estimator_->compensator().inner.load(setup.weights);
  estimator_->set_compensated_joints(
      compensated_joints(setup.weights, N, setup.parameters.compensator_min_held_out_gain));
}

template <int N>
SteppedEstimator<N>::~SteppedEstimator() = default;

template <int N>
const EstimatorOutput<double, N>& SteppedEstimator<N>::update(
    const ReplaySample<N>& sample) noexcept {
  return estimator_->update(sample);
}

SensorNoise estimate_sensor_noise(const Log& log, const Eigen::VectorXd& torque_constant,
                                  std::vector<int>* never_rests) {
  SensorNoise noise;
  const std::string effort = log.effort_prefix();
  if (torque_constant.size() != log.joint_count())
    throw Error::at(log.source, 0, "", "torque constants for another joint count");
  const DriveUnits units{effort_unit_of_column(effort), torque_constant};
  const double rate = log.quality.rate_hz;  // the time column's where the metadata contradicts it
  const double period = std::isfinite(rate) && rate > 0 ? 1.0 / rate : 0.0025;
  const int joints = log.joint_count();
  noise.effort.resize(joints);
  noise.effort_step.resize(joints);
  if (never_rests) never_rests->clear();
  for (int j = 0; j < joints; ++j) {
    noise.effort_step[j] = units.to_torque(j, 1.0);
    try {
      noise.effort[j] = units.to_torque(j, effort_noise(log, effort, j + 1, period));
    } catch (const Error&) {
      if (!never_rests) throw;
      never_rests->push_back(j);
      noise.effort[j] = std::numeric_limits<double>::quiet_NaN();
    }
  }
  if (never_rests && !never_rests->empty()) {
    const double largest = noise.effort.array().isFinite().select(noise.effort, 0.0).maxCoeff();
    for (int j : *never_rests)
      noise.effort[j] = largest;
  }
  noise.pad_kpa = pad_noise(log);
  return noise;
}

template <int N>
EstimatorParameters<double, N> estimator_parameters_from_noise(const SensorNoise& noise,
                                                               double pad_gain_kpa_per_n) {
  EstimatorParameters<double, N> p;
  if (noise.effort.size() != N || noise.effort_step.size() != N)
    throw Error("sensor noise of " + std::to_string(noise.effort.size()) + " joints for a " +
                std::to_string(N) + "-joint estimator");
  const int window =
      static_cast<int>(std::lround(p.static_friction.baseline_window_s / p.sample_period_s));
  // The effort is rounded to 1 unit of the log: its variance adds step²/12.
  const JointVector<double, N> sigma =
      (noise.effort.array().square() + noise.effort_step.array().square() / 12.0).sqrt().matrix();
  p.static_dead_band = static_dead_band_from_noise<double, N>(sigma, window);
  if (noise.pad_kpa > 0)
    p.skin.detector = detector_settings_from_noise(noise.pad_kpa, p.sample_period_s, 0.0105);
  p.skin.force_gain = 1.0 / (pad_gain_kpa_per_n * 1000.0 * 0.0025);
  return p;
}

template <int N>
EstimatorTrace replay_estimator(const EstimatorSetup<N>& setup,
                                const std::vector<ReplaySample<N>>& samples) {
  return with_estimator(setup, [&](auto& e) { return trace_estimator(e, samples); });
}

template <int N>
JointVector<double, N> speed_envelope(const std::vector<ReplaySample<N>>& samples) {
  JointVector<double, N> v = JointVector<double, N>::Zero();
  for (const ReplaySample<N>& s : samples)
    if (std::isfinite(s.t) && s.dq.allFinite()) v = v.cwiseMax(s.dq.cwiseAbs());
  return v;
}

template <int N>
JointVector<double, N> acceleration_envelope(const EstimatorTrace& tr) {
  JointVector<double, N> a = JointVector<double, N>::Zero();
  const auto ddq = tr.inputs.middleCols<N>(2 * N);  // compensator_input
  for (Eigen::Index k = 0; k < tr.rows(); ++k)
    if (ddq.row(k).allFinite()) a = a.cwiseMax(ddq.row(k).transpose().cwiseAbs());
  return a;
}

template <int N>
TransitionSigma<double, N> calibrate_sigma(EstimatorSetup<N>& setup,
                                           const std::vector<ReplaySample<N>>& samples,
                                           const std::string& source) {
  const auto sigma = with_estimator(
      setup, [&](auto& e) { return calibrate_transition_sigma(e, samples, 0.07, source); });
  setup.parameters.nominal_sigma = sigma.nominal;
  setup.parameters.fused_sigma = sigma.fused;
  return sigma;
}

#define TPF_INSTANTIATE_REPLAY(N)                                                                \
  template EstimatorParameters<double, N> estimator_parameters_from_noise<N>(const SensorNoise&, \
                                                                             double);            \
  template EstimatorTrace replay_estimator<N>(const EstimatorSetup<N>&,                          \
                                              const std::vector<ReplaySample<N>>&);              \
  template JointVector<double, N> speed_envelope<N>(const std::vector<ReplaySample<N>>&);        \
  template JointVector<double, N> acceleration_envelope<N>(const EstimatorTrace&);               \
  template TransitionSigma<double, N> calibrate_sigma<N>(                                        \
      EstimatorSetup<N>&, const std::vector<ReplaySample<N>>&, const std::string&);              \
  template class SteppedEstimator<N>;
TPF_FOR_EACH_JOINT_COUNT(TPF_INSTANTIATE_REPLAY)
#undef TPF_INSTANTIATE_REPLAY

}  // namespace tpf::offline
