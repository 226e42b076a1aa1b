#include "offline/training/arm_estimator.hpp"

#include <algorithm>
#include <cmath>

#include "tpf/common/error.hpp"
#include "tpf/estimation/transition_sigma.hpp"

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

/// The offline tools' compensator: the network, recording the input the estimator built.
template <typename Compensator>
using Recording = RecordingCompensator<Compensator, double, kArmJoints>;

}  // namespace

SensorNoise estimate_sensor_noise(const Log& log) {
  SensorNoise noise;
  const std::string effort = log.effort_prefix();
  const Eigen::VectorXd t = log.col("t");
  const double rate = log.meta.rate_hz();
  const double period = std::isfinite(rate) ? 1.0 / rate : 0.0025;
  for (int j = 0; j < kArmJoints; ++j) {
    const auto dq = log.col(indexed_name("dq", j + 1));
    const auto e = log.col(indexed_name(effort, j + 1));
    std::vector<double> d;
    for (Eigen::Index k = 1; k < log.rows(); ++k) {
      const bool rest = std::abs(dq[k]) < 1e-4 && std::abs(dq[k - 1]) < 1e-4;
      if (rest && t[k] - t[k - 1] < 1.5 * period && std::isfinite(e[k] - e[k - 1]))
        d.push_back(e[k] - e[k - 1]);
    }
    if (d.size() < 10)
      throw Error::at(log.source, 0, indexed_name(effort, j + 1),
                      "too few static rows to estimate the effort noise");
    noise.effort[j] = robust_std(d) / std::sqrt(2.0);
  }
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
  noise.pad_kpa = d.empty() ? 0.0 : robust_std(d) / std::sqrt(2.0);
  return noise;
}

ArmParameters arm_estimator_parameters(const SensorNoise& noise, double pad_gain_kpa_per_n) {
  ArmParameters p;
  const int window =
      static_cast<int>(std::lround(p.static_friction.baseline_window_s / p.sample_period_s));
  // The effort is rounded to 1 unit: its variance adds 1/12.
  const JointVector<double, kArmJoints> sigma =
      (noise.effort.array().square() + 1.0 / 12.0).sqrt().matrix();
  p.static_dead_band = static_dead_band_from_noise<double, kArmJoints>(sigma, window);
  if (noise.pad_kpa > 0)
    p.skin.detector = detector_settings_from_noise(noise.pad_kpa, p.sample_period_s, 0.0105);
  p.skin.force_gain = 1.0 / (pad_gain_kpa_per_n * 1000.0 * 0.0025);
  return p;
}

EstimatorTrace trace_arm_estimator(const ArmEstimatorSetup& setup,
                                   const std::vector<ArmSample>& samples) {
  return with_arm_estimator<Recording>(setup, [&](auto& e) { return trace_estimator(e, samples); });
}

JointVector<double, kArmJoints> speed_envelope(const std::vector<ArmSample>& samples) {
  JointVector<double, kArmJoints> v = JointVector<double, kArmJoints>::Zero();
  for (const ArmSample& s : samples)
    if (std::isfinite(s.t) && s.dq.allFinite()) v = v.cwiseMax(s.dq.cwiseAbs());
  return v;
}

JointVector<double, kArmJoints> acceleration_envelope(const EstimatorTrace& tr) {
  JointVector<double, kArmJoints> a = JointVector<double, kArmJoints>::Zero();
  const auto ddq = tr.inputs.middleCols<kArmJoints>(2 * kArmJoints);  // compensator_input
  for (Eigen::Index k = 0; k < tr.rows(); ++k)
    if (ddq.row(k).allFinite()) a = a.cwiseMax(ddq.row(k).transpose().cwiseAbs());
  return a;
}

TransitionSigma<double, kArmJoints> calibrate_arm_sigma(ArmEstimatorSetup& setup,
                                                        const std::vector<ArmSample>& samples,
                                                        const std::string& source) {
  const auto sigma = with_arm_estimator<Recording>(
      setup, [&](auto& e) { return calibrate_transition_sigma(e, samples, 0.07, source); });
  setup.parameters.nominal_sigma = sigma.nominal;
  setup.parameters.fused_sigma = sigma.fused;
  return sigma;
}

}  // namespace tpf::offline
