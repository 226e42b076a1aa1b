#include "offline/measured_study/sensor_candidates.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "offline/log/torque_sensor.hpp"
#include "offline/measured_study/noise_floor.hpp"
#include "offline/report/text_format.hpp"
#include "offline/signal/causal_low_pass.hpp"
#include "offline/signal/periodogram.hpp"

namespace tpf::offline {
namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

/// The columns of one candidate at sample k of joint j of a side (at most 8: no heap).
using CandidateFeatureVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 8, 1>;
using CandidateFeatures =
    std::function<CandidateFeatureVector(const JointSamples&, Eigen::Index, int)>;

bool candidate_moving(const JointSamples& s, Eigen::Index k, int j) {
  const Regime r = s.regimes[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
  return r == Regime::StaticToKinetic || r == Regime::Moving;
}

double motion_direction(const JointSamples& s, Eigen::Index k, int j) {
  return candidate_moving(s, k, j) ? (s.dq(k, j) > 0 ? 1.0 : -1.0) : 0.0;
}

/// r − Φθ over the side, NaN where r is NaN or a feature is not finite.
Eigen::VectorXd minus_candidate_fit(const JointSamples& s, const Eigen::VectorXd& r, int j,
                                    const CandidateFeatures& phi, const Eigen::VectorXd& theta) {
  Eigen::VectorXd out(r.size());
  for (Eigen::Index k = 0; k < r.size(); ++k) {
    if (!std::isfinite(r[k])) {
      out[k] = kNoValue;
      continue;
    }
    const CandidateFeatureVector f = phi(s, k, j);
    out[k] = f.allFinite() ? r[k] - f.dot(theta) : kNoValue;
  }
  return out;
}

/// Least squares of r on the candidate's columns over the finite rows (tiny ridge).
Eigen::VectorXd fit_candidate(const JointSamples& s, const Eigen::VectorXd& r, int j,
                              const CandidateFeatures& phi, int columns) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(columns, columns);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(columns);
  for (Eigen::Index k = 0; k < r.size(); ++k) {
    if (!std::isfinite(r[k])) continue;
    const CandidateFeatureVector f = phi(s, k, j);
    if (!f.allFinite()) continue;
    A += f * f.transpose();
    b += f * r[k];
  }
  A.diagonal().array() += 1e-9 * std::max(A.diagonal().maxCoeff(), 1e-300);
  return A.ldlt().solve(b);
}

/// The n in [lo, hi] whose sin/cos of n·q best explains r on the finite moving samples.
int dominant_ripple_cycles(const JointSamples& s, const Eigen::VectorXd& r, int j, int lo, int hi) {
  std::vector<double> q_moving, r_moving;
  for (Eigen::Index k = 0; k < r.size(); ++k)
    if (std::isfinite(r[k]) && candidate_moving(s, k, j)) {
      q_moving.push_back(s.q(k, j));
      r_moving.push_back(r[k]);
    }
  const auto as_vector = [](const std::vector<double>& v) {
    return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  };
  return static_cast<int>(dominant_cycles(as_vector(q_moving), as_vector(r_moving), lo, hi, 1.0));
}

double moving_range_of(const JointSamples& s, const Eigen::VectorXd& r, int j) {
  double lo = 1e300, hi = -1e300;
  for (Eigen::Index k = 0; k < r.size(); ++k)
    if (std::isfinite(r[k]) && candidate_moving(s, k, j)) {
      lo = std::min(lo, s.q(k, j));
      hi = std::max(hi, s.q(k, j));
    }
  return hi > lo ? hi - lo : 0.0;
}

/// The residual with the sensor read `shift` samples later (same file, usable sensor only).
Eigen::VectorXd sensor_shifted(const SensorSide& side, const Eigen::VectorXd& r, int j, int shift) {
  const Log& log = *side.log;
  const int sensor = log.column(indexed_name("tau_sensor", j + 1));
  Eigen::VectorXd out = Eigen::VectorXd::Constant(r.size(), kNoValue);
  for (std::size_t f = 0; f < log.file_count(); ++f) {
    const auto [begin, end] = log.file_rows(f);
    for (Eigen::Index k = begin; k < end; ++k) {
      const Eigen::Index m = k + shift;
      if (m < begin || m >= end || !std::isfinite(r[k]) || !std::isfinite(r[m])) continue;
      out[k] = r[k] + log.values(k, sensor) - log.values(m, sensor);
    }
  }
  return out;
}

/// The residual with the current through causal_low_pass of time constant `tau` [s]:
/// r + (LP(K_t·i) − K_t·i).
Eigen::VectorXd current_low_passed(const SensorSide& side, const Eigen::VectorXd& r, int j,
                                   double tau) {
  const JointSamples& s = *side.samples;
  const Eigen::VectorXd e = s.effort.col(j);
  return r + (causal_low_pass(s.t, e, tau, side.log->file_starts) - e);
}

/// Restricts a to the rows where b is finite.
Eigen::VectorXd restricted_to_finite(Eigen::VectorXd a, const Eigen::VectorXd& b) {
  for (Eigen::Index k = 0; k < a.size(); ++k)
    if (!std::isfinite(b[k])) a[k] = kNoValue;
  return a;
}

/// The candidate's columns after the base's.
CandidateFeatures with_base_columns(const CandidateFeatures& base, int base_columns,
                                    const CandidateFeatures& phi, int columns) {
  return [=](const JointSamples& s, Eigen::Index k, int j) {
    CandidateFeatureVector f(base_columns + columns);
    f << base(s, k, j), phi(s, k, j);
    return f;
  };
}

/// RMSE on the fitting and the held-out side of r − Φθ, θ fitted on the fitting side.
std::pair<double, double> fitted_candidate_rms(const JointSamples& fs, const Eigen::VectorXd& rf,
                                               const JointSamples& hs, const Eigen::VectorXd& rh,
                                               int j, const CandidateFeatures& phi, int columns,
                                               Eigen::VectorXd* theta_out) {
  const Eigen::VectorXd theta = fit_candidate(fs, rf, j, phi, columns);
  if (theta_out) *theta_out = theta;
  return {finite_rms(minus_candidate_fit(fs, rf, j, phi, theta)),
          finite_rms(minus_candidate_fit(hs, rh, j, phi, theta))};
}

struct CandidateEffect {
  std::string key, title;
  int columns;
  CandidateFeatures phi;
  std::string detail;
};

}  // namespace

Eigen::MatrixXd sensor_residual(const SensorSide& side) {
  const Log& log = *side.log;
  const JointSamples& s = *side.samples;
  const int joints = s.joints();
  const auto sensors = torque_sensor_columns(log, joints);
  Eigen::MatrixXd r = Eigen::MatrixXd::Constant(s.size(), joints, kNoValue);
  for (int j = 0; j < joints; ++j) {
    const int sensor = log.column(indexed_name("tau_sensor", j + 1));
    if (sensor < 0) continue;
    for (std::size_t f = 0; f < log.file_count(); ++f) {
      if (!sensor_usable(sensors, f, j)) continue;
      const auto [begin, end] = log.file_rows(f);
      for (Eigen::Index k = begin; k < end; ++k)
        if (s.valid[static_cast<std::size_t>(k)])
          r(k, j) = s.effort(k, j) - side.drive_loss(k, j) - log.values(k, sensor);
    }
  }
  return r;
}

std::vector<SensorCandidate> sensor_candidates(const SensorSide& fit_side,
                                               const SensorSide& held_side,
                                               const Eigen::VectorXd& gear_ratio,
                                               const SensorCandidateOptions& o) {
  const Eigen::MatrixXd r_fit = sensor_residual(fit_side);
  const Eigen::MatrixXd r_held = sensor_residual(held_side);
  const JointSamples& fs = *fit_side.samples;
  const JointSamples& hs = *held_side.samples;
  const bool thermal = fs.temperature.cols() == fs.joints() && hs.temperature.cols() == hs.joints();
  std::vector<SensorCandidate> out;
  for (int j = 0; j < fs.joints(); ++j) {
    const Eigen::VectorXd rf = r_fit.col(j), rh = r_held.col(j);
    const double before_fit = finite_rms(rf), before_held = finite_rms(rh);
    if (!std::isfinite(before_fit) || !std::isfinite(before_held)) continue;
    double mean_temperature = 0;
    if (thermal) {
      double n = 0;
      for (Eigen::Index k = 0; k < rf.size(); ++k)
        if (std::isfinite(rf[k])) mean_temperature += fs.temperature(k, j), ++n;
      mean_temperature /= std::max(n, 1.0);
    }
    const double ratio = gear_ratio[j];
    const double range = moving_range_of(fs, rf, j);
    const int shortest = shortest_fitting_cycles(range);
    const int cycles = shortest <= o.max_ripple_cycles
                           ? dominant_ripple_cycles(fs, rf, j, shortest, o.max_ripple_cycles)
                           : 0;
    std::vector<CandidateEffect> library{
        {"offset", "constant offset (sensor zero, friction held at rest)", 1,
         [](const JointSamples&, Eigen::Index, int) { return CandidateFeatureVector::Ones(1); },
         ""},
        {"kt_error", "torque constant error (K_t·i scaled)", 1,
         [&](const JointSamples& s, Eigen::Index k, int jj) {
           return CandidateFeatureVector::Constant(1, s.effort(k, jj));
         },
         ""},
        {"load_friction", "load-dependent friction (|K_t·i|·sgn q̇)", 1,
         [&](const JointSamples& s, Eigen::Index k, int jj) {
           return CandidateFeatureVector::Constant(
               1, std::abs(s.effort(k, jj)) * motion_direction(s, k, jj));
         },
         ""},
        {"held_friction", "friction held at rest (last direction of motion)", 1,
         [](const JointSamples& s, Eigen::Index k, int jj) {
           return CandidateFeatureVector::Constant(
               1, candidate_moving(s, k, jj) ? 0.0 : s.held_sign(k, jj));
         },
         ""},
        {"ripple_motor", "strain-wave ripple (1 and 2 periods per motor revolution)", 4,
         [ratio](const JointSamples& s, Eigen::Index k, int jj) {
           const double a = ratio * s.q(k, jj);
           CandidateFeatureVector f(4);
           f << std::sin(a), std::cos(a), std::sin(2 * a), std::cos(2 * a);
           return f;
         },
         format_sentence("gear ratio %.0f", ratio)}};
    if (cycles > 0)
      library.push_back({"ripple_output", "position ripple of the output", 2,
                         [cycles](const JointSamples& s, Eigen::Index k, int jj) {
                           CandidateFeatureVector f(2);
                           f << std::sin(cycles * s.q(k, jj)), std::cos(cycles * s.q(k, jj));
                           return f;
                         },
                         format_sentence("%.0f periods/rev (shortest that fits the motion: %.0f)",
                                         cycles, shortest)});
    if (thermal)
      library.push_back({"temperature", "temperature-dependent friction ((T − T̄)·sgn q̇, (T − T̄)·q̇)",
                         2,
                         [mean_temperature](const JointSamples& s, Eigen::Index k, int jj) {
                           const double d = s.temperature(k, jj) - mean_temperature;
                           CandidateFeatureVector f(2);
                           f << d * motion_direction(s, k, jj), d * s.dq(k, jj);
                           return f;
                         },
                         format_sentence("T̄ = %.1f °C", mean_temperature)});
    // The base every other candidate is judged on: Coulomb + viscous refitted against the
    // sensor (what is left is beyond a friction curve's level and slope).
    const CandidateFeatures base = [](const JointSamples& s, Eigen::Index k, int jj) {
      CandidateFeatureVector f(2);
      f << motion_direction(s, k, jj), s.dq(k, jj);
      return f;
    };
    Eigen::VectorXd base_theta;
    const auto [base_fit, base_held] =
        fitted_candidate_rms(fs, rf, hs, rh, j, base, 2, &base_theta);
    out.push_back({"friction_refit", "Coulomb + viscous refitted against the sensor", j,
                   format_sentence("τ_c %+.3g N·m, b %+.3g N·m·s/rad on top of the model's",
                                   base_theta[0], base_theta[1]),
                   before_fit, base_fit, before_held, base_held, false});
    for (const CandidateEffect& c : library) {
      Eigen::VectorXd theta;
      const auto [after_fit, after_held] = fitted_candidate_rms(
          fs, rf, hs, rh, j, with_base_columns(base, 2, c.phi, c.columns), c.columns + 2, &theta);
      SensorCandidate sc{c.key,     c.title,   j,          c.detail, base_fit,
                         after_fit, base_held, after_held, false};
      theta = theta.tail(c.columns).eval();
      if (c.key == "kt_error")
        sc.detail = format_sentence("K_t × %.3f", 1.0 - theta[0]);
      else if (c.key == "offset")
        sc.detail = format_sentence("%.3g N·m", theta[0]);
      else if (c.key == "load_friction")
        sc.detail = format_sentence("%.3g N·m per N·m", theta[0]);
      out.push_back(sc);
    }
    // Lag: the sensor read later (positive) or earlier than the current, chosen in-file.
    const int max_shift =
        static_cast<int>(std::round(o.max_lag_s / std::max(fs.t[1] - fs.t[0], 1e-6)));
    // (judged on the base refitted on each shifted residual, over the rows every shift has;
    // 2-sample steps)
    const Eigen::VectorXd common = restricted_to_finite(
        sensor_shifted(fit_side, rf, j, max_shift), sensor_shifted(fit_side, rf, j, -max_shift));
    int best = 0;
    double best_rms = std::numeric_limits<double>::infinity();
    for (int shift = -(max_shift / 2) * 2; shift <= max_shift; shift += 2) {
      const Eigen::VectorXd r =
          restricted_to_finite(sensor_shifted(fit_side, rf, j, shift), common);
      const double now =
          finite_rms(minus_candidate_fit(fs, r, j, base, fit_candidate(fs, r, j, base, 2)));
      if (now < best_rms) best_rms = now, best = shift;
    }
    const Eigen::VectorXd lag_fit = sensor_shifted(fit_side, rf, j, best);
    const Eigen::VectorXd lag_held = sensor_shifted(held_side, rh, j, best);
    const auto [lag_fit_rms, lag_held_rms] =
        fitted_candidate_rms(fs, lag_fit, hs, lag_held, j, base, 2, nullptr);
    const auto [same_fit_rms, same_held_rms] =
        fitted_candidate_rms(fs, restricted_to_finite(rf, lag_fit), hs,
                             restricted_to_finite(rh, lag_held), j, base, 2, nullptr);
    // Current noise: the sensor is far smoother than K_t·i; a causal low-pass of the current,
    // its time constant chosen in-file.
    double best_tau = 0.0, best_low = base_fit;
    for (double tau : kCurrentLowPassTimeConstants) {
      const double now = fitted_candidate_rms(fs, current_low_passed(fit_side, rf, j, tau), fs, rf,
                                              j, base, 2, nullptr)
                             .first;
      if (now < best_low) best_low = now, best_tau = tau;
    }
    if (best_tau > 0) {
      const auto [low_fit, low_held] =
          fitted_candidate_rms(fs, current_low_passed(fit_side, rf, j, best_tau), hs,
                               current_low_passed(held_side, rh, j, best_tau), j, base, 2, nullptr);
      out.push_back(
          {"current_low_pass", "current noise: causal low-pass of K_t·i", j,
           format_sentence("time constant %.0f ms (chosen in-file from 2–200 ms)", 1000 * best_tau),
           base_fit, low_fit, base_held, low_held, false});
    } else {
      out.push_back({"current_low_pass", "current noise: causal low-pass of K_t·i", j,
                     "no time constant lowers the in-file error", base_fit, base_fit, base_held,
                     base_held, false});
    }
    out.push_back({"lag", "lag between current and torque sensor", j,
                   format_sentence("%+.0f ms (chosen in-file from ±%.0f ms)",
                                   1000.0 * best * (fs.t[1] - fs.t[0]), 1000 * o.max_lag_s),
                   same_fit_rms, lag_fit_rms, same_held_rms, lag_held_rms, false});
  }
  for (SensorCandidate& c : out)
    c.supported =
        c.fit_after < c.fit_before && c.heldout_after <= (1 - o.min_gain) * c.heldout_before;
  return out;
}

}  // namespace tpf::offline
