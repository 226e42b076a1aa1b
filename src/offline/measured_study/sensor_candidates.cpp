#include "offline/measured_study/sensor_candidates.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "offline/effects/design_context.hpp"
#include "offline/effects/effort_scale_columns.hpp"
#include "offline/effects/joint_friction_columns.hpp"
#include "offline/effects/load_friction_columns.hpp"
#include "offline/effects/motor_ripple_columns.hpp"
#include "offline/effects/offset_columns.hpp"
#include "offline/effects/output_ripple_columns.hpp"
#include "offline/effects/sample_row.hpp"
#include "offline/effects/selected_columns.hpp"
#include "offline/effects/thermal_coulomb_columns.hpp"
#include "offline/effects/thermal_friction_columns.hpp"
#include "offline/measured_study/noise_floor.hpp"
#include "offline/report/text_format.hpp"
#include "offline/signal/periodogram.hpp"

namespace tpf::offline {
namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();

/// The base: JointFrictionColumns' Coulomb and viscous columns s, q̇ (its column of the friction
/// held at rest is the held_friction candidate).
using FrictionBaseColumns = SelectedColumns<JointFrictionColumns, JointFrictionColumns::kCoulomb,
                                            JointFrictionColumns::kViscous>;
using HeldFrictionColumns =
    SelectedColumns<JointFrictionColumns, JointFrictionColumns::kHeldAtRest>;
/// LoadFrictionColumns' Coulomb column |load|·s, the load being the measured |K_t·i| here (the
/// sides' CandidateInputs::abs_gravity hold it in place of the model's |G_j(q)|).
using EffortLoadFrictionColumns = SelectedColumns<LoadFrictionColumns, 0>;

/// A candidate's columns of joint row `joint` of a sample: registry families' fill().
using CandidateFill = std::function<void(const SampleRow&, int joint, double* out)>;

/// One row of the base's and a candidate's columns (at most 8: no heap).
using CandidateRow = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 8, 1>;

bool candidate_moving(const JointSamples& s, Eigen::Index k, int j) {
  const Regime r = s.regimes[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)];
  return r == Regime::StaticToKinetic || r == Regime::Moving;
}

/// One side's samples as the registry's families see them, a SampleRow at a time. Moving = the
/// regimes StaticToKinetic and Moving: the direction s = sgn(q̇_j) there (else 0), the held sign h
/// elsewhere (else 0).
class SideRows {
 public:
  SideRows(const JointSamples& s, const Eigen::VectorXd& gear_ratio)
      : samples_(s),
        gear_ratio_(gear_ratio),
        q_(s.joints()),
        dq_(s.joints()),
        ddq_(s.joints()),
        direction_(s.joints()),
        held_(s.joints()) {
    inputs.ripple_cycles = inputs.ripple_periods = Eigen::VectorXd::Zero(s.joints());
    inputs.ripple_motor_cycles = Eigen::VectorXd::Ones(s.joints());  // 1 period per motor rev
    inputs.abs_gravity = s.effort.cwiseAbs();                        // the load: |K_t·i|
  }

  /// What the families read besides the samples (set per joint by the caller).
  CandidateInputs inputs;

  /// The columns `fill` gives joint j at every sample (samples × width).
  Eigen::MatrixXd columns(int j, int width, const CandidateFill& fill) {
    Eigen::MatrixXd out(samples_.size(), width);
    CandidateRow f(width);
    for (Eigen::Index k = 0; k < samples_.size(); ++k) {
      fill(row(k), j, f.data());
      out.row(k) = f.transpose();
    }
    return out;
  }

 private:
  SampleRow row(Eigen::Index k) {
    const JointSamples& s = samples_;
    q_ = s.q.row(k).transpose();
    dq_ = s.dq.row(k).transpose();
    ddq_ = s.ddq.row(k).transpose();
    for (int j = 0; j < s.joints(); ++j) {
      const bool moving = candidate_moving(s, k, j);
      direction_[j] = moving ? (s.dq(k, j) > 0 ? 1.0 : -1.0) : 0.0;
      held_[j] = moving ? 0.0 : s.held_sign(k, j);
    }
    return {{q_, dq_, ddq_, gear_ratio_},
            no_regressor_,
            direction_,
            held_,
            no_base_columns_,
            inputs,
            s,
            k};
  }

  const JointSamples& samples_;
  const Eigen::VectorXd& gear_ratio_;
  Eigen::VectorXd q_, dq_, ddq_, direction_, held_;
  const Eigen::MatrixXd no_regressor_;  ///< none of the study's families reads the regressor
  const std::vector<int> no_base_columns_;
};

/// [a b]: the base's columns, then a candidate's.
Eigen::MatrixXd side_by_side(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd out(a.rows(), a.cols() + b.cols());
  out << a, b;
  return out;
}

/// r − Xθ, NaN where r is NaN or a column is not finite.
Eigen::VectorXd minus_fit(const Eigen::MatrixXd& X, const Eigen::VectorXd& r,
                          const Eigen::VectorXd& theta) {
  Eigen::VectorXd out(r.size());
  for (Eigen::Index k = 0; k < r.size(); ++k) {
    if (!std::isfinite(r[k])) {
      out[k] = kNoValue;
      continue;
    }
    const CandidateRow f = X.row(k).transpose();
    out[k] = f.allFinite() ? r[k] - f.dot(theta) : kNoValue;
  }
  return out;
}

/// Least squares of r on the columns X over the finite rows (tiny ridge).
Eigen::VectorXd least_squares_fit(const Eigen::MatrixXd& X, const Eigen::VectorXd& r) {
  const Eigen::Index columns = X.cols();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(columns, columns);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(columns);
  for (Eigen::Index k = 0; k < r.size(); ++k) {
    if (!std::isfinite(r[k])) continue;
    const CandidateRow f = X.row(k).transpose();
    if (!f.allFinite()) continue;
    A += f * f.transpose();
    b += f * r[k];
  }
  A.diagonal().array() += 1e-9 * std::max(A.diagonal().maxCoeff(), 1e-300);
  return A.ldlt().solve(b);
}

/// RMSE on the fitting and the held-out side of r − Xθ, θ fitted on the fitting side.
std::pair<double, double> fitted_rms(const Eigen::MatrixXd& Xf, const Eigen::VectorXd& rf,
                                     const Eigen::MatrixXd& Xh, const Eigen::VectorXd& rh,
                                     Eigen::VectorXd* theta_out = nullptr) {
  const Eigen::VectorXd theta = least_squares_fit(Xf, rf);
  if (theta_out) *theta_out = theta;
  return {finite_rms(minus_fit(Xf, rf, theta)), finite_rms(minus_fit(Xh, rh, theta))};
}

/// Restricts a to the rows where b is finite.
Eigen::VectorXd restricted_to_finite(Eigen::VectorXd a, const Eigen::VectorXd& b) {
  for (Eigen::Index k = 0; k < a.size(); ++k)
    if (!std::isfinite(b[k])) a[k] = kNoValue;
  return a;
}

/// The output ripple r of joint j holds on the fitting side, over its finite moving samples
/// (output_ripple: diagnose's search, a real number of periods per revolution).
OutputRipple fitted_output_ripple(const JointSamples& s, const Eigen::VectorXd& r, int j,
                                  int highest) {
  std::vector<double> q_moving, r_moving;
  for (Eigen::Index k = 0; k < r.size(); ++k)
    if (std::isfinite(r[k]) && candidate_moving(s, k, j)) {
      q_moving.push_back(s.q(k, j));
      r_moving.push_back(r[k]);
    }
  const auto as_vector = [](const std::vector<double>& v) {
    return Eigen::VectorXd(
        Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())));
  };
  return output_ripple(as_vector(q_moving), as_vector(r_moving), highest);
}

/// The mean temperature of joint j over the samples where r is finite.
double mean_temperature(const JointSamples& s, const Eigen::VectorXd& r, int j) {
  double sum = 0, n = 0;
  for (Eigen::Index k = 0; k < r.size(); ++k)
    if (std::isfinite(r[k])) sum += s.temperature(k, j), ++n;
  return sum / std::max(n, 1.0);
}

struct CandidateEffect {
  std::string key, title;
  int columns;
  CandidateFill fill;
  std::string detail;
};

/// The candidate `key` of one registry family: its columns of joint j (its group's width).
template <typename Family>
CandidateEffect family_effect(std::string key, std::string title, const DesignContext& context,
                              int j, std::string detail = "") {
  return {std::move(key), std::move(title),
          static_cast<int>(Family::group(context, j).column_names.size()), &Family::fill,
          std::move(detail)};
}

}  // namespace

std::vector<SensorCandidate> sensor_candidates(const SensorSide& fit_side,
                                               const SensorSide& held_side,
                                               const Eigen::VectorXd& gear_ratio,
                                               const SensorCandidateOptions& o) {
  const Eigen::MatrixXd r_fit = sensor_residual(fit_side);
  const Eigen::MatrixXd r_held = sensor_residual(held_side);
  const JointSamples& fs = *fit_side.samples;
  const JointSamples& hs = *held_side.samples;
  const int joints = fs.joints();
  const bool thermal = fs.temperature.cols() == joints && hs.temperature.cols() == joints;
  SideRows fit_rows(fs, gear_ratio), held_rows(hs, gear_ratio);
  // The strain-wave gear's second period per motor revolution: MotorRippleColumns read with these.
  CandidateInputs twice_per_motor_rev;
  twice_per_motor_rev.ripple_motor_cycles = Eigen::VectorXd::Constant(joints, 2.0);
  const std::vector<int> no_base_columns;
  std::vector<SensorCandidate> out;
  for (int j = 0; j < joints; ++j) {
    const Eigen::VectorXd rf = r_fit.col(j), rh = r_held.col(j);
    const double before_fit = finite_rms(rf), before_held = finite_rms(rh);
    if (!std::isfinite(before_fit) || !std::isfinite(before_held)) continue;
    // The base every other candidate is judged on: Coulomb + viscous refitted against the
    // sensor (what is left is beyond a friction curve's level and slope).
    const int base_width = FrictionBaseColumns::kColumns;
    const Eigen::MatrixXd base_fit = fit_rows.columns(j, base_width, &FrictionBaseColumns::fill);
    const Eigen::MatrixXd base_held = held_rows.columns(j, base_width, &FrictionBaseColumns::fill);
    Eigen::VectorXd base_theta;
    const auto [base_fit_rms, base_held_rms] = fitted_rms(base_fit, rf, base_held, rh, &base_theta);
    // What the families read for joint j, the same on both sides (fitted on the fitting side;
    // the ripple's frequency on what the base leaves).
    const double temperature = thermal ? mean_temperature(fs, rf, j) : 0.0;
    const OutputRipple ripple =
        fitted_output_ripple(fs, minus_fit(base_fit, rf, base_theta), j, o.max_ripple_cycles);
    for (CandidateInputs* inputs : {&fit_rows.inputs, &held_rows.inputs}) {
      inputs->reference_temperature = temperature;
      inputs->ripple_cycles[j] = ripple.cycles;
      inputs->ripple_periods[j] = ripple.periods;
    }
    const DesignContext context{joints, no_base_columns, fit_rows.inputs, thermal, false};
    const double ratio = gear_ratio[j];
    std::vector<CandidateEffect> library{
        family_effect<OffsetColumns>(
            "offset", "constant offset (sensor zero, friction held at rest)", context, j),
        family_effect<EffortScaleColumns>("kt_error", "torque constant error (K_t·i scaled)",
                                          context, j),
        family_effect<EffortLoadFrictionColumns>(
            "load_friction", "load-dependent friction (|K_t·i|·sgn q̇)", context, j),
        family_effect<HeldFrictionColumns>(
            "held_friction", "friction held at rest (last direction of motion)", context, j),
        {"ripple_motor", "strain-wave ripple (1 and 2 periods per motor revolution)", 4,
         [&twice_per_motor_rev](const SampleRow& row, int jj, double* f) {
           MotorRippleColumns::fill(row, jj, f);
           MotorRippleColumns::fill({row.motion, row.regressor, row.direction, row.held,
                                     row.base_columns, twice_per_motor_rev, row.samples, row.k},
                                    jj, f + 2);
         },
         format_sentence("gear ratio %.0f", ratio)}};
    // Under one period in the range of motion the registry's ripple names no frequency: it
    // cannot be told from the families it is judged beside (an offset, a spring).
    std::string ripple_ambiguous_with;
    if (OutputRippleColumns::offered(context, j)) {
      const GroupSpec group = OutputRippleColumns::group(context, j);
      if (group.indistinct_from_beside)
        ripple_ambiguous_with = joined(group.judged_beside, " and ");
      library.push_back(family_effect<OutputRippleColumns>(
          "ripple_output", "position ripple of the output", context, j,
          ripple_ambiguous_with.empty()
              ? format_sentence("%.4g periods/rev (%.3g periods in the range of motion)",
                                ripple.cycles, ripple.periods)
              : format_sentence("%.3g periods in the range of motion: its frequency (%.4g "
                                "periods/rev fitted) is not named",
                                ripple.periods, ripple.cycles) +
                    ", ambiguous with the " + ripple_ambiguous_with));
    }
    if (ThermalCoulombColumns::offered(context, j) && ThermalFrictionColumns::offered(context, j))
      library.push_back({"temperature", "temperature-dependent friction ((T − T̄)·sgn q̇, (T − T̄)·q̇)",
                         2,
                         [](const SampleRow& row, int jj, double* f) {
                           ThermalCoulombColumns::fill(row, jj, f);
                           ThermalFrictionColumns::fill(row, jj, f + 1);
                         },
                         format_sentence("T̄ = %.1f °C", temperature)});
    out.push_back({"friction_refit", "Coulomb + viscous refitted against the sensor", j,
                   format_sentence("τ_c %+.3g N·m, b %+.3g N·m·s/rad on top of the model's",
                                   base_theta[0], base_theta[1]),
                   kNoValue, "", before_fit, base_fit_rms, before_held, base_held_rms, false});
    for (const CandidateEffect& c : library) {
      Eigen::VectorXd theta;
      const auto [after_fit, after_held] =
          fitted_rms(side_by_side(base_fit, fit_rows.columns(j, c.columns, c.fill)), rf,
                     side_by_side(base_held, held_rows.columns(j, c.columns, c.fill)), rh, &theta);
      SensorCandidate sc{c.key,     c.title,       j,          c.detail, kNoValue, "", base_fit_rms,
                         after_fit, base_held_rms, after_held, false};
      theta = theta.tail(c.columns).eval();
      if (c.key == "kt_error") {
        sc.value = 1.0 - theta[0];
        sc.detail = format_sentence("K_t × %.3f", sc.value);
      } else if (c.key == "offset") {
        sc.value = theta[0];
        sc.detail = format_sentence("%.3g N·m", sc.value);
      } else if (c.key == "load_friction") {
        sc.value = theta[0];
        sc.detail = format_sentence("%.3g N·m per N·m", sc.value);
      } else if (c.key == "ripple_output") {
        sc.value = ripple.cycles;
        sc.ambiguous_with = ripple_ambiguous_with;
      }
      out.push_back(sc);
    }
    // Lag: the sensor read later (positive) or earlier than the current, chosen in-file.
    const double step = fs.t[1] - fs.t[0];
    const int max_shift = static_cast<int>(std::round(o.max_lag_s / std::max(step, 1e-6)));
    // (judged on the base refitted on each shifted residual, over the rows every shift has;
    // 2-sample steps)
    const Eigen::VectorXd common = restricted_to_finite(
        sensor_shifted(fit_side, rf, j, max_shift), sensor_shifted(fit_side, rf, j, -max_shift));
    int best = 0;
    double best_rms = std::numeric_limits<double>::infinity();
    for (int shift = -(max_shift / 2) * 2; shift <= max_shift; shift += 2) {
      const Eigen::VectorXd r =
          restricted_to_finite(sensor_shifted(fit_side, rf, j, shift), common);
      const double now = finite_rms(minus_fit(base_fit, r, least_squares_fit(base_fit, r)));
      if (now < best_rms) best_rms = now, best = shift;
    }
    const Eigen::VectorXd lag_fit = sensor_shifted(fit_side, rf, j, best);
    const Eigen::VectorXd lag_held = sensor_shifted(held_side, rh, j, best);
    const auto [lag_fit_rms, lag_held_rms] = fitted_rms(base_fit, lag_fit, base_held, lag_held);
    const auto [same_fit_rms, same_held_rms] = fitted_rms(
        base_fit, restricted_to_finite(rf, lag_fit), base_held, restricted_to_finite(rh, lag_held));
    // Current noise: the sensor is far smoother than K_t·i; a causal low-pass of the current,
    // its time constant chosen in-file.
    double best_tau = 0.0, best_low = base_fit_rms;
    for (double tau : kCurrentLowPassTimeConstants) {
      const double now =
          fitted_rms(base_fit, current_low_passed(fit_side, rf, j, tau), base_fit, rf).first;
      if (now < best_low) best_low = now, best_tau = tau;
    }
    if (best_tau > 0) {
      const auto [low_fit, low_held] =
          fitted_rms(base_fit, current_low_passed(fit_side, rf, j, best_tau), base_held,
                     current_low_passed(held_side, rh, j, best_tau));
      out.push_back(
          {"current_low_pass", "current noise: causal low-pass of K_t·i", j,
           format_sentence("time constant %.0f ms (chosen in-file from 2–200 ms)", 1000 * best_tau),
           1000 * best_tau, "", base_fit_rms, low_fit, base_held_rms, low_held, false});
    } else {
      out.push_back({"current_low_pass", "current noise: causal low-pass of K_t·i", j,
                     "no time constant lowers the in-file error", kNoValue, "", base_fit_rms,
                     base_fit_rms, base_held_rms, base_held_rms, false});
    }
    out.push_back({"lag", "lag between current and torque sensor", j,
                   format_sentence("%+.0f ms (chosen in-file from ±%.0f ms)", 1000.0 * best * step,
                                   1000 * o.max_lag_s),
                   1000.0 * best * step, "", same_fit_rms, lag_fit_rms, same_held_rms, lag_held_rms,
                   false});
  }
  for (SensorCandidate& c : out)
    c.supported =
        c.fit_after < c.fit_before && c.heldout_after <= (1 - o.min_gain) * c.heldout_before;
  return out;
}

}  // namespace tpf::offline
