#include "offline/measured_study/measured_bound.hpp"

#include <cmath>
#include <limits>

#include "offline/measured_study/coverage_share.hpp"
#include "offline/measured_study/low_pass_choice.hpp"
#include "offline/measured_study/noise_floor.hpp"
#include "offline/measured_study/sensor_residual.hpp"

namespace tpf::offline {
namespace {

std::vector<double> bound_rmse(const Eigen::MatrixXd& residual) {
  return finite_rms_per_column(residual);
}

std::vector<double> bound_values(const Eigen::VectorXd& v) {
  return {v.data(), v.data() + v.size()};
}

/// x where `mask` is finite, NaN elsewhere.
Eigen::MatrixXd bound_masked(const Eigen::MatrixXd& x, const Eigen::MatrixXd& mask) {
  return mask.array().isFinite().select(x, std::numeric_limits<double>::quiet_NaN());
}

}  // namespace

std::vector<double> heldout_sensor_rmse(const MeasuredBoundSide& side,
                                        const EffortEstimate& estimate) {
  return bound_rmse(sensor_residual({side.log, side.samples, estimate.drive_loss}));
}

MeasuredBound measured_bound(const MeasuredBoundSide& fit, const MeasuredBoundSide& scored,
                             const EffortEstimate& fit_estimate, const EffortEstimate& heldout,
                             const EffortEstimate& in_sample, double target_reduction,
                             double low_hz, double high_hz) {
  const Log& log = *scored.log;
  const JointSamples& s = *scored.samples;
  const JointSamples& fs = *fit.samples;
  MeasuredBound b;
  b.low_hz = low_hz;
  b.high_hz = high_hz;
  const Eigen::MatrixXd kt_only =
      sensor_residual({&log, &s, Eigen::MatrixXd::Zero(s.size(), s.joints())});
  b.maker = bound_rmse(kt_only);
  for (double m : b.maker)
    b.target.push_back((1.0 - target_reduction) * m);
  const Eigen::MatrixXd residual = sensor_residual({&log, &s, heldout.drive_loss});
  b.heldout = bound_rmse(residual);
  const Eigen::MatrixXd fit_residual = sensor_residual({fit.log, &fs, fit_estimate.drive_loss});
  b.fit_time_constants =
      choose_current_low_pass(*fit.log, fs, fit_residual, LowPassCriterion::kPooled).time_constant;
  b.heldout_low_pass = bound_rmse(low_passed_residual(log, s, residual, b.fit_time_constants));
  b.worst_file_time_constants =
      choose_current_low_pass(*fit.log, fs, fit_residual, LowPassCriterion::kWorstFile)
          .time_constant;
  b.heldout_worst_file =
      bound_rmse(low_passed_residual(log, s, residual, b.worst_file_time_constants));
  const LowPassChoice oracle = choose_current_low_pass(log, s, residual, LowPassCriterion::kPooled);
  b.oracle_time_constants = oracle.time_constant;
  b.oracle_low_pass = bound_values(oracle.rmse);
  const Eigen::MatrixXd own = sensor_residual({&log, &s, in_sample.drive_loss});
  b.in_sample = bound_rmse(own);
  const LowPassChoice both = choose_current_low_pass(log, s, own, LowPassCriterion::kPooled);
  b.in_sample_time_constants = both.time_constant;
  b.in_sample_low_pass = bound_values(both.rmse);

  const BandRms bands = band_rms(log, s.t, residual, low_hz, high_hz);
  b.band_low = bands.low, b.band_mid = bands.mid, b.band_high = bands.high;
  b.in_sample_band_low = band_rms(log, s.t, own, low_hz, high_hz).low;
  b.current_mid = band_rms(log, s.t, bound_masked(s.effort, residual), low_hz, high_hz).mid;
  const Eigen::MatrixXd sensor = kt_only - s.effort;  // −τ_sensor where scored
  b.sensor_mid = band_rms(log, s.t, sensor, low_hz, high_hz).mid;

  const CoverageShare c = coverage_share(fs, fit_residual, s, residual);
  b.velocity_samples = c.velocity_samples, b.velocity_error = c.velocity_error;
  b.position_samples = c.position_samples, b.position_error = c.position_error;
  b.fit_velocity_min = c.fit_velocity_min, b.fit_velocity_max = c.fit_velocity_max;

  b.fit_dq = bound_masked(fs.dq.leftCols(fit_residual.cols()), fit_residual);
  b.fit_loss = fit_residual + fit_estimate.drive_loss;
  b.scored_dq = bound_masked(s.dq.leftCols(residual.cols()), residual);
  b.scored_loss = residual + heldout.drive_loss;
  b.model_loss = bound_masked(heldout.drive_loss, residual);
  return b;
}

}  // namespace tpf::offline
