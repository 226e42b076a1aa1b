#include "offline/diagnose/residual_analysis.hpp"

#include <algorithm>
#include <cmath>

#include "offline/fit/parallel_jobs.hpp"
#include "offline/regimes/regime.hpp"
#include "offline/report/text_format.hpp"
#include "offline/signal/acceleration.hpp"
#include "offline/signal/periodogram.hpp"
#include "offline/signal/segments.hpp"

namespace tpf::offline {
namespace {

// Std of the effort's first difference over consecutive static samples, /√2 (NaN: never rests).
double static_noise(const JointSamples& s, int j) {
  double sum = 0, count = 0;
  for (Eigen::Index k = 1; k < s.size(); ++k)
    if (s.valid[k] && s.valid[k - 1] && s.regimes[j][k] == Regime::Static &&
        s.regimes[j][k - 1] == Regime::Static) {
      sum += std::pow(s.effort(k, j) - s.effort(k - 1, j), 2);
      ++count;
    }
  return count > 0 ? std::sqrt(sum / count / 2.0) : std::nan("");
}

// RMS of the effort above `band_hz` (effort − its zero-phase low-pass) over the moving samples of
// joint j, the held-out ones where some are (the rows the moving held-out error is of); NaN: it
// never moves there, or the band reaches the Nyquist frequency 1/(2·step).
double motion_noise(const JointSamples& s, int j, double band_hz, double step) {
  if (!(band_hz < 0.45 / step)) return std::nan("");
  Eigen::VectorXd effort = s.effort.col(j);
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (!s.valid[k]) effort[k] = std::nan("");
  const Eigen::VectorXd smooth = zero_phase_low_pass(s.t, effort, band_hz, step);
  const bool heldout_only = holds_rows_out(s);
  double sum = 0, count = 0;
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s.valid[k] && (!heldout_only || s.heldout[k]) && s.regimes[j][k] == Regime::Moving &&
        std::isfinite(smooth[k])) {
      sum += std::pow(effort[k] - smooth[k], 2);
      ++count;
    }
  return count > 0 ? std::sqrt(sum / count) : std::nan("");
}

// The training samples where joint j moves.
std::vector<Eigen::Index> moving_training_samples(const JointSamples& s, int j) {
  std::vector<Eigen::Index> moving;
  for (Eigen::Index k = 1; k < s.size(); ++k)
    if (s.valid[k] && !s.heldout[k] && s.regimes[j][k] == Regime::Moving) moving.push_back(k);
  return moving;
}

// q_j and r at most 20 000 of the `moving` samples, evenly strided (the periodograms' input);
// false when there are 100 or fewer.
bool strided_moving_samples(const JointSamples& s, const Eigen::VectorXd& residual, int j,
                            const std::vector<Eigen::Index>& moving, Eigen::VectorXd& q,
                            Eigen::VectorXd& r) {
  const std::size_t stride = std::max<std::size_t>(1, moving.size() / 20000);
  const Eigen::Index m = static_cast<Eigen::Index>(moving.size() / stride);
  if (m <= 100) return false;
  q.resize(m);
  r.resize(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    q[i] = s.q(moving[i * stride], j);
    r[i] = residual[moving[i * stride]];
  }
  return true;
}

// (1 + ρ)/(1 − ρ) of the residual's lag-1 autocorrelation over consecutive moving samples.
double variance_inflation(const Eigen::VectorXd& residual,
                          const std::vector<Eigen::Index>& moving) {
  double num = 0, den = 0;
  for (std::size_t i = 1; i < moving.size(); ++i)
    if (moving[i] == moving[i - 1] + 1) {
      num += residual[moving[i]] * residual[moving[i - 1]];
      den += residual[moving[i]] * residual[moving[i]];
    }
  const double rho = den > 0 ? std::clamp(num / den, 0.0, 0.995) : 0.0;
  return (1 + rho) / (1 - rho);
}

/// Joint j's part of the analysis: its entries of `a`, and its notes into `notes`.
void analyse_joint_residual(const JointSamples& s, const Eigen::MatrixXd& residual,
                            const Eigen::VectorXd& gear_ratio, double step, double band_hz, int j,
                            ResidualAnalysis& a, std::vector<std::string>& notes) {
  a.noise_floor[j] = static_noise(s, j);
  a.motion_noise[j] = motion_noise(s, j, band_hz, step);
  const std::vector<Eigen::Index> moving = moving_training_samples(s, j);
  a.variance_inflation[j] = variance_inflation(residual.col(j), moving);
  Eigen::VectorXd q, r;
  if (!strided_moving_samples(s, residual.col(j), j, moving, q, r)) return;
  // Output side: from half a period in the range (at least 3/rev) to 64/rev (output_ripple).
  const OutputRipple ripple = output_ripple(q, r, 64);
  const double range = ripple.range;
  a.ripple_cycles[j] = ripple.cycles;
  a.ripple_periods[j] = ripple.periods;
  const double one_period = std::min(2 * M_PI / std::max(range, 1e-9), 1e6);
  if (one_period > 3)
    notes.push_back("joint " + std::to_string(j + 1) +
                    format_sentence(": moves over %.2f rad, so a position ripple of fewer than "
                                    "%.3g periods/rev shows under one period there: its "
                                    "frequency is not named (ambiguous with an offset and a "
                                    "spring)",
                                    range, one_period));
  const double gear = std::abs(gear_ratio[j]);
  a.ripple_motor_cycles[j] = fitted_cycles(q, r, 0.5, 4.5, gear);
  a.ripple_motor_periods[j] = a.ripple_motor_cycles[j] * gear * range / (2 * M_PI);
}

}  // namespace

OutputRipple joint_output_ripple(const JointSamples& s, const Eigen::VectorXd& residual, int j) {
  Eigen::VectorXd q, r;
  if (!strided_moving_samples(s, residual, j, moving_training_samples(s, j), q, r)) return {};
  return output_ripple(q, r, 64);
}

ResidualAnalysis analyse_residual(const JointSamples& s, const Eigen::MatrixXd& residual,
                                  const Eigen::MatrixXd& rigid_prediction,
                                  const Eigen::VectorXd& gear_ratio, double model_band_hz) {
  const int joints = static_cast<int>(residual.cols());
  ResidualAnalysis a;
  a.noise_floor.resize(joints);
  a.motion_noise.resize(joints);
  a.variance_inflation = Eigen::VectorXd::Ones(joints);
  a.ripple_cycles = Eigen::VectorXd::Zero(joints);
  a.ripple_motor_cycles = Eigen::VectorXd::Zero(joints);
  a.ripple_periods = Eigen::VectorXd::Zero(joints);
  a.ripple_motor_periods = Eigen::VectorXd::Zero(joints);
  // Joints are independent: each thread takes the next (same result as serial, notes in joint
  // order).
  std::vector<std::vector<std::string>> notes(static_cast<std::size_t>(joints));
  const double step = median_step(s.t);  // once for every joint's filter
  parallel_jobs(joints, [&](int j) {
    analyse_joint_residual(s, residual, gear_ratio, step, model_band_hz, j, a,
                           notes[static_cast<std::size_t>(j)]);
  });
  a.effort_lag = search_effort_lag(s, rigid_prediction, residual, 0.1);
  for (const std::vector<std::string>& joint_notes : notes)
    a.notes.insert(a.notes.end(), joint_notes.begin(), joint_notes.end());
  return a;
}

}  // namespace tpf::offline
