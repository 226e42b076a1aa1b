// Calibration of the dead bands: σ of the estimation error in the static-to-kinetic transition,
// measured on contact-free data (start-up / offline code).
#pragma once

#include <array>
#include <cmath>
#include <string>

#include "tpf/common/error.hpp"
#include "tpf/common/types.hpp"
#include "tpf/estimation/estimator_status.hpp"

namespace tpf {

/// Per joint σ [N·m] of the nominal residual τ_res and of the compensated residual
/// τ_res − τ_TCN in the static-to-kinetic transition, and how many samples each rests on.
/// At Eigen::Dynamic the vectors are sized by calibrate_transition_sigma.
template <typename S, int N>
struct TransitionSigma {
  JointVector<S, N> nominal = zero_or_empty<JointVector<S, N>>();
  JointVector<S, N> fused = zero_or_empty<JointVector<S, N>>();
  LinkArray<long, N> samples{};
};

/// Runs `estimator` (reset first) over `samples` of a contact-free log in time order. There the
/// true external torque is zero, so every residual is estimation error. Joint j is in its
/// static-to-kinetic transition from the first sample where the estimator's tracker no longer
/// has it at rest (|q̇_j| ≥ v_s, the estimator's static velocity; with a coupled transmission a
/// motor acting on it turning, |(C·q̇)_m| ≥ v_s) after a sample at rest, for `window_s` seconds
/// (the original work's ≈70 ms) or until it is at rest again. Over those samples
///   σ_nominal,j = √(mean τ_res,j²),   σ_fused,j = √(mean (τ_res,j − τ_TCN,j)²)
/// (root mean square about zero: a bias is error too). Skipped samples (status bits non-finite /
/// stale) are ignored. Store the result with estimator.set_transition_sigma(σ.nominal, σ.fused).
/// Throws tpf::Error naming `source` when a joint has no transition in the data.
template <typename EstimatorT, typename SampleRange>
auto calibrate_transition_sigma(EstimatorT& estimator, const SampleRange& samples,
                                double window_s = 0.07, const std::string& source = "samples") {
  using Output = std::decay_t<decltype(estimator.output())>;
  using S = std::decay_t<decltype(Output{}.t)>;
  constexpr int N = decltype(Output{}.residual)::RowsAtCompileTime;
  const int n = estimator.nominal().model.joint_count();

  TransitionSigma<S, N> sigma;
  sigma.nominal = sigma.fused = JointVector<S, N>::Zero(n);
  resize_storage(sigma.samples, static_cast<std::size_t>(n));
  JointVector<S, N> sum_nominal = JointVector<S, N>::Zero(n), sum_fused = sum_nominal;
  LinkArray<bool, N> was_static{}, in_window{};
  LinkArray<S, N> start{};
  resize_storage(was_static, static_cast<std::size_t>(n));
  resize_storage(in_window, static_cast<std::size_t>(n));
  resize_storage(start, static_cast<std::size_t>(n));
  bool first = true;
  estimator.reset();
  for (const auto& sample : samples) {
    const Output& out = estimator.update(sample);
    if (out.status & (kStatusNonFiniteInput | kStatusStaleTime)) continue;
    for (int j = 0; j < n; ++j) {
      const bool is_static = estimator.tracker().is_static(j);  // rest per motor where coupled
      if (!first && was_static[j] && !is_static) {
        in_window[j] = true;
        start[j] = out.t;
      }
      if (is_static || out.t - start[j] >= S(window_s)) in_window[j] = false;
      if (in_window[j]) {
        const S e = out.residual[j], f = out.residual[j] - out.compensation[j];
        sum_nominal[j] += e * e;
        sum_fused[j] += f * f;
        ++sigma.samples[j];
      }
      was_static[j] = is_static;
    }
    first = false;
  }
  for (int j = 0; j < n; ++j) {
    if (sigma.samples[j] == 0) {
      throw Error::at(source, 0, "joint " + std::to_string(j + 1),
                      "no static-to-kinetic transition to calibrate the dead band on");
    }
    sigma.nominal[j] = std::sqrt(sum_nominal[j] / S(sigma.samples[j]));
    sigma.fused[j] = std::sqrt(sum_fused[j] / S(sigma.samples[j]));
  }
  return sigma;
}

}  // namespace tpf
