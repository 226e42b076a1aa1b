#include "offline/identify/identify.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>

#include "offline/effects/effect_columns.hpp"
#include "offline/fit/gram_fit.hpp"
#include "offline/fit/parallel_halves.hpp"
#include "offline/fit/parallel_jobs.hpp"
#include "offline/identify/effect_design.hpp"
#include "offline/identify/identification_setup.hpp"
#include "offline/identify/inertia_prior.hpp"
#include "offline/identify/linear_friction_fit.hpp"
#include "offline/identify/sensor_friction.hpp"
#include "offline/identify/stribeck_fit.hpp"
#include "offline/report/text_format.hpp"
#include "tpf/common/error.hpp"
#include "tpf/model/robot_description.hpp"

namespace tpf::offline {

std::vector<RegimeStats> split_regime_stats(const JointSamples& s, const Eigen::MatrixXd& residual,
                                            bool heldout) {
  std::vector<RegimeStats> stats;
  for (int j = 0; j < s.joints(); ++j) {
    Eigen::VectorXd r = residual.col(j);
    for (Eigen::Index k = 0; k < r.size(); ++k)
      if (static_cast<bool>(s.heldout[k]) != heldout)
        r[k] = std::numeric_limits<double>::quiet_NaN();
    stats.push_back(regime_stats(r, s.regimes[j]));
  }
  return stats;
}

std::vector<Eigen::MatrixXd> nominal_residuals(const std::vector<const NominalModelX*>& nominals,
                                               const JointSamples& s) {
  const Eigen::Index n = s.size();
  const int joints = s.joints();
  std::vector<Eigen::MatrixXd> residuals;
  std::vector<NominalLinks<double, Eigen::Dynamic>> links;  // once per model, not per sample
  for (const NominalModelX* nominal : nominals) {
    residuals.emplace_back(n, joints);
    links.push_back(nominal_links(*nominal));
  }
  if (nominals.empty()) return residuals;
  auto work = [&](Eigen::Index begin, Eigen::Index end) {
    DataX data(nominals.front()->model);
    // Sized once, assigned per sample.
    Eigen::VectorXd q(joints), dq(joints), ddq(joints), rigid(joints), friction(joints);
    for (Eigen::Index k = begin; k < end; ++k) {
      if (!s.valid[k]) {
        for (Eigen::MatrixXd& residual : residuals)
          residual.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      q = s.q.row(k).transpose();
      dq = s.dq.row(k).transpose();
      ddq = s.ddq.row(k).transpose();
      forward_kinematics(nominals.front()->model, data, q);
      for (std::size_t m = 0; m < nominals.size(); ++m) {
        predict_effort_at_pose(*nominals[m], links[m], data, q, dq, ddq, rigid, friction);
        residuals[m].row(k) = s.effort.row(k) - (rigid + friction).transpose();
      }
    }
  };
  parallel_halves(n, work);
  return residuals;
}

Eigen::MatrixXd nominal_residual(const NominalModelX& nominal, const JointSamples& s) {
  return std::move(nominal_residuals({&nominal}, s).front());
}

std::vector<Eigen::VectorXd> mass_check_poses(const ModelX& model) {
  std::mt19937_64 rng(7);
  auto uniform = [&rng](double lo, double hi) {
    return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
  };
  const int joints = model.joint_count();
  std::vector<Eigen::VectorXd> poses(200, Eigen::VectorXd(joints));
  for (Eigen::VectorXd& q : poses)
    for (int j = 0; j < joints; ++j)
      q[j] =
          model.has_position_limits(j) ? uniform(model.lower[j], model.upper[j]) : uniform(-3, 3);
  return poses;
}

double min_mass_eigenvalue(const NominalModelX& nominal) {
  const int joints = nominal.model.joint_count();
  DataX data(nominal.model);
  Eigen::MatrixXd Y;
  double min_eigen = std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& q : mass_check_poses(nominal.model)) {
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(joints);
    const Eigen::VectorXd g = rigid_body_torque(nominal, data, Y, q, zero, zero);
    Eigen::MatrixXd M(joints, joints);
    for (int i = 0; i < joints; ++i)
      M.col(i) = rigid_body_torque(nominal, data, Y, q, zero, Eigen::VectorXd::Unit(joints, i)) - g;
    const Eigen::MatrixXd sym = 0.5 * (M + M.transpose());
    min_eigen = std::min(min_eigen,
                         Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(sym, Eigen::EigenvaluesOnly)
                             .eigenvalues()
                             .minCoeff());
  }
  return min_eigen;
}

ConsistencyCheck check_consistency(const NominalModelX& nominal) {
  ConsistencyCheck check;
  const double min_eigen = min_mass_eigenvalue(nominal);
  check.min_mass_eigenvalue = min_eigen;
  check.checks.push_back("mass matrix M(q) (rigid body + armature) positive definite at 200 poses");
  if (!(min_eigen > 0))
    check.problems.push_back(
        "M(q) is not positive definite (smallest eigenvalue " + std::to_string(min_eigen) +
        " kg·m²): the log does not excite every inertia the base parameters hold (too short, too "
        "little acceleration, or joints that never accelerate independently), so the identified "
        "inertial torque is not physical; log a longer excitation that accelerates every joint, "
        "and judge the model on held-out data (tpf validate)");
  check.checks.push_back("friction: τ_c, τ_s, b, α ≥ 0, q̇_s > 0");
  const StribeckParametersX& f = nominal.friction;
  for (int j = 0; j < nominal.model.joint_count(); ++j) {
    const std::string joint = "joint " + std::to_string(j + 1);
    if (!(f.coulomb[j] >= 0) || !(f.static_friction[j] >= 0) || !(f.viscous[j] >= 0))
      check.problems.push_back(joint + ": negative Coulomb, static or viscous friction");
    if (!(f.load_coulomb[j] >= 0) || !(f.load_viscous[j] >= 0))
      check.problems.push_back(joint + ": negative load-dependent friction");
    if (!(f.stribeck_velocity[j] > 0)) check.problems.push_back(joint + ": q̇_s ≤ 0");
  }
  return check;
}

namespace {

// Where plain least squares of τ_c·sgn(q̇) + b·q̇ (either sign) beats the written friction on the
// held-out samples by more than 0.5 %, it is because a coefficient is negative: the target falls
// with speed faster than any dissipative curve (all coefficients ≥ 0) can follow. Said, with both
// RMS values; the written friction keeps its bounds.
template <typename Target>
void note_non_dissipative_linear(const Eigen::MatrixXd& training,
                                 const std::vector<Eigen::Index>& heldout, const Target& target_at,
                                 const Eigen::Ref<const Eigen::VectorXd>& dq, double sse_written,
                                 const std::string& joint, std::vector<std::string>& notes) {
  if (heldout.empty()) return;
  const JointStribeck free =
      fit_linear_friction(training.col(0), training.col(1), training.col(2), false, false);
  double sse_free = 0;
  for (Eigen::Index k : heldout) {
    const double v = dq[k], sign = v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0);
    sse_free += std::pow(target_at(k) - free.coulomb * sign - free.viscous * v, 2);
  }
  if (sse_written <= 1.005 * 1.005 * sse_free) return;
  const double n = static_cast<double>(heldout.size());
  char text[512];
  std::snprintf(text, sizeof text,
                "plain least squares τ_c·sgn(q̇) + b·q̇ gives τ_c = %.3g, b = %.3g and a held-out "
                "RMS of %.4g against the written friction's %.4g: the target falls with speed "
                "faster than a dissipative curve (coefficients ≥ 0) can follow, which points at "
                "an effect correlated with speed that is not friction; the bounds are kept",
                free.coulomb, free.viscous, std::sqrt(sse_free / n), std::sqrt(sse_written / n));
  notes.push_back(joint + text);
}

// The RMS of the linear candidate's residual on the samples `x` (columns q̇, |G|, target): the
// scale of the Stribeck fit's Cauchy loss, the typical sliding misfit, so that the onsets and
// reversals (residuals of several times it) weigh less than the sliding samples.
double linear_residual_rms(const Eigen::MatrixXd& x, const JointStribeck& linear) {
  const Eigen::ArrayXd v = x.col(0).array(), g = x.col(1).array();
  const Eigen::ArrayXd fitted = (linear.coulomb + linear.load_coulomb * g) * v.sign() +
                                (linear.viscous + linear.load_viscous * g) * v;
  return std::sqrt((x.col(2).array() - fitted).square().mean());
}

// Joint j's curve in fit_stribeck's terms.
JointStribeck joint_stribeck(const StribeckParametersX& p, int j) {
  return {p.coulomb[j], p.static_friction[j], p.stribeck_velocity[j], p.stribeck_exponent[j],
          p.viscous[j], p.load_coulomb[j],    p.load_viscous[j]};
}

// fit_friction_curves, and with `judged` refit_friction_curves (every row; each joint's choice
// and curve from `judged`).
FrictionCurves friction_curves(const JointSamples& s, const Eigen::MatrixXd& rigid_prediction,
                               const Eigen::MatrixXd& abs_gravity,
                               const StribeckParametersX& linear, bool fit_load,
                               int samples_per_joint, const FrictionCurves* judged,
                               const Eigen::MatrixXd* coupling) {
  const int joints = s.joints();
  // A coupled model: motor m's curve on its velocity (C·q̇)_m against the motor-side target
  // (C⁻ᵀ·(effort − rigid))_m; rows as samples, so velocity = q̇·Cᵀ and target = residual·C⁻¹.
  const bool coupled = coupling && !coupling->isIdentity(0.0);
  Eigen::MatrixXd motor_dq, motor_residual;
  std::vector<std::vector<int>> motor_joints(static_cast<std::size_t>(joints));
  if (coupled) {
    const Eigen::MatrixXd inverse = coupling->inverse();
    motor_dq = s.dq * coupling->transpose();
    motor_residual = (s.effort - rigid_prediction) * inverse;
    for (int m = 0; m < joints; ++m)
      for (int j = 0; j < joints; ++j)
        if ((*coupling)(m, j) != 0.0 || inverse(j, m) != 0.0)
          motor_joints[static_cast<std::size_t>(m)].push_back(j);
  }
  const Eigen::MatrixXd& velocity = coupled ? motor_dq : s.dq;
  // Motor j moves at sample k (the joint's regime where each joint is its own motor).
  auto moving = [&](int j, Eigen::Index k) {
    if (!coupled)
      return s.regimes[j][k] != Regime::Static && s.regimes[j][k] != Regime::Invalid &&
             std::isfinite(rigid_prediction(k, j));
    if (!(std::abs(motor_dq(k, j)) >= 1e-4) || !std::isfinite(motor_residual(k, j))) return false;
    for (int i : motor_joints[static_cast<std::size_t>(j)])
      if (s.regimes[i][k] == Regime::Invalid) return false;
    return true;
  };
  FrictionCurves out;
  out.parameters = linear;
  out.linear_written.assign(static_cast<std::size_t>(joints), 0);
  out.heldout_rms_curve = Eigen::VectorXd::Constant(joints, std::nan(""));
  out.heldout_rms_linear = out.heldout_rms_curve;
  StribeckParametersX clamped = linear;  // what the linear fit can write
  for (int j = 0; j < joints; ++j) {
    clamped.coulomb[j] = clamped.static_friction[j] = std::max(linear.coulomb[j], 0.0);
    clamped.viscous[j] = std::max(linear.viscous[j], 0.0);
    clamped.load_coulomb[j] = std::max(linear.load_coulomb[j], 0.0);
    clamped.load_viscous[j] = std::max(linear.load_viscous[j], 0.0);
    clamped.coulomb_asymmetry[j] =
        std::clamp(linear.coulomb_asymmetry[j], -clamped.coulomb[j], clamped.coulomb[j]);
  }
  std::vector<std::vector<std::string>> notes(static_cast<std::size_t>(joints));
  // A joint whose gravity torque stays negligible (a vertical axis) has no load column to fit:
  // α·|G| there would fit noise in |G| with an absurd α.
  Eigen::Index largest_row = 0, largest_joint = 0;
  const double arm_gravity = abs_gravity.array()
                                 .isFinite()
                                 .select(abs_gravity, 0.0)
                                 .maxCoeff(&largest_row, &largest_joint);
  auto fit_joint = [&](int j) {
    std::vector<Eigen::Index> rows, heldout;
    for (Eigen::Index k = 0; k < s.size(); ++k)
      if (s.valid[k] && moving(j, k)) (s.heldout[k] && !judged ? heldout : rows).push_back(k);
    // Friction target without the held terms (asymmetry, neighbour load), and the linear curve.
    Eigen::VectorXd abs_g(joints);  // sized once, assigned per sample
    auto target_at = [&](Eigen::Index k) {
      abs_g = abs_gravity.row(k).transpose();
      const double dq = velocity(k, j);
      const double held = clamped.coulomb_asymmetry[j] * (dq != 0.0) +
                          clamped.viscous_asymmetry[j] * std::abs(dq) +
                          neighbour_load_friction(clamped, j, dq, abs_g);
      return (coupled ? motor_residual(k, j) : s.effort(k, j) - rigid_prediction(k, j)) - held;
    };
    if (rows.size() < 50) {
      out.linear_written[static_cast<std::size_t>(j)] = 1;
      out.parameters.coulomb[j] = out.parameters.static_friction[j] = clamped.coulomb[j];
      out.parameters.viscous[j] = clamped.viscous[j];
      notes[j].push_back("joint " + std::to_string(j + 1) + ": fewer than 50 moving samples, " +
                         "the linear Coulomb + viscous fit is kept");
      return;
    }
    const std::size_t stride =
        std::max<std::size_t>(1, rows.size() / static_cast<std::size_t>(samples_per_joint));
    // The linear candidate and the curve's start: Coulomb + viscous by least squares on every
    // training sample of this friction target, both ≥ 0 (load terms would overfit a log that
    // loads a joint one way; the curve fits them).
    auto gather = [&](std::size_t step) {
      const Eigen::Index m = static_cast<Eigen::Index>((rows.size() + step - 1) / step);
      Eigen::MatrixXd x(m, 3);  // q̇, |G|, target
      for (Eigen::Index i = 0; i < m; ++i) {
        const Eigen::Index k = rows[static_cast<std::size_t>(i) * step];
        x.row(i) << velocity(k, j), abs_gravity(k, j), target_at(k);
      }
      return x;
    };
    const Eigen::MatrixXd all = gather(1);
    const JointStribeck start = fit_linear_friction(all.col(0), all.col(1), all.col(2), false);
    StribeckParametersX linear_fit = clamped;
    linear_fit.coulomb[j] = linear_fit.static_friction[j] = start.coulomb;
    linear_fit.viscous[j] = start.viscous;
    linear_fit.load_coulomb[j] = start.load_coulomb;
    linear_fit.load_viscous[j] = start.load_viscous;
    const bool fit_load_here = fit_load && all.col(1).maxCoeff() > 1e-3 * arm_gravity;
    if (fit_load && !fit_load_here)
      notes[j].push_back("joint " + std::to_string(j + 1) + ": its gravity torque stays below " +
                         "0.1 % of the arm's largest (joint " + std::to_string(largest_joint + 1) +
                         "'s, " + format_number(arm_gravity, 3) +
                         " N·m, or N at a prismatic joint): no load-dependent friction fitted");
    auto write_linear = [&] {
      out.linear_written[static_cast<std::size_t>(j)] = 1;
      out.parameters.coulomb[j] = out.parameters.static_friction[j] = linear_fit.coulomb[j];
      out.parameters.viscous[j] = linear_fit.viscous[j];
      out.parameters.load_coulomb[j] = linear_fit.load_coulomb[j];
      out.parameters.load_viscous[j] = linear_fit.load_viscous[j];
      out.parameters.coulomb_asymmetry[j] =
          std::clamp(clamped.coulomb_asymmetry[j], -linear_fit.coulomb[j], linear_fit.coulomb[j]);
    };
    if (judged && judged->linear_written[static_cast<std::size_t>(j)]) {
      write_linear();  // the final fit on every row: the choice made on the held-out rows
      return;
    }
    const Eigen::MatrixXd strided = gather(stride);
    const double scale = linear_residual_rms(all, start);
    const StribeckFit fit =
        judged ? refine_stribeck(strided.col(0), strided.col(1), strided.col(2),
                                 joint_stribeck(judged->parameters, j), fit_load_here, scale)
               : fit_stribeck(strided.col(0), strided.col(1), strided.col(2), start, fit_load_here,
                              scale);
    StribeckParametersX curve = clamped;
    curve.coulomb[j] = fit.curve.coulomb;
    curve.static_friction[j] = fit.curve.static_friction;
    curve.stribeck_velocity[j] = fit.curve.stribeck_velocity;
    curve.stribeck_exponent[j] = fit.curve.stribeck_exponent;
    curve.viscous[j] = fit.curve.viscous;
    curve.load_coulomb[j] = fit.curve.load_coulomb;
    curve.load_viscous[j] = fit.curve.load_viscous;
    // Held-out comparison with the linear fit on the same samples.
    double sse_curve = 0, sse_linear = 0;
    // The symmetric part of a curve (the asymmetry is held, the same in both).
    auto symmetric = [&](const StribeckParametersX& p, Eigen::Index k) {
      const double v = velocity(k, j);
      return stribeck_friction(p, j, v, abs_gravity(k, j)) - p.coulomb_asymmetry[j] * (v != 0.0) -
             p.viscous_asymmetry[j] * std::abs(v);
    };
    for (Eigen::Index k : heldout) {
      const double t = target_at(k);
      sse_curve += std::pow(t - symmetric(curve, k), 2);
      sse_linear += std::pow(t - symmetric(linear_fit, k), 2);
    }
    const std::string joint = "joint " + std::to_string(j + 1) + ": ";
    note_non_dissipative_linear(all, heldout, target_at, velocity.col(j),
                                std::min(sse_curve, sse_linear), joint, notes[j]);
    if (!heldout.empty()) {
      out.heldout_rms_curve[j] = std::sqrt(sse_curve / static_cast<double>(heldout.size()));
      out.heldout_rms_linear[j] = std::sqrt(sse_linear / static_cast<double>(heldout.size()));
    }
    if (!heldout.empty() && sse_curve > sse_linear) {
      char text[256];
      std::snprintf(text, sizeof text,
                    "the Stribeck curve's held-out RMS (%.4g) is above the linear Coulomb + "
                    "viscous fit's (%.4g) on the same samples: the linear fit is written",
                    out.heldout_rms_curve[j], out.heldout_rms_linear[j]);
      notes[j].push_back(joint + text);
      write_linear();
      return;
    }
    for (const std::string& b : fit.at_bound)
      notes[j].push_back(joint + "Stribeck fit: " + b);
    out.parameters.coulomb[j] = curve.coulomb[j];
    out.parameters.static_friction[j] = curve.static_friction[j];
    out.parameters.stribeck_velocity[j] = curve.stribeck_velocity[j];
    out.parameters.stribeck_exponent[j] = curve.stribeck_exponent[j];
    out.parameters.viscous[j] = curve.viscous[j];
    out.parameters.load_coulomb[j] = curve.load_coulomb[j];
    out.parameters.load_viscous[j] = curve.load_viscous[j];
    out.parameters.coulomb_asymmetry[j] =
        std::clamp(clamped.coulomb_asymmetry[j], -curve.coulomb[j], curve.coulomb[j]);
  };
  // Joints are independent problems of unequal cost: each thread takes the next joint (same
  // result as serial).
  parallel_jobs(joints, fit_joint);
  for (const auto& n : notes)
    out.notes.insert(out.notes.end(), n.begin(), n.end());
  return out;
}

}  // namespace

FrictionCurves fit_friction_curves(const JointSamples& s, const Eigen::MatrixXd& rigid_prediction,
                                   const Eigen::MatrixXd& abs_gravity,
                                   const StribeckParametersX& linear, bool fit_load,
                                   int samples_per_joint, const Eigen::MatrixXd* coupling) {
  return friction_curves(s, rigid_prediction, abs_gravity, linear, fit_load, samples_per_joint,
                         nullptr, coupling);
}

StribeckParametersX refit_friction_curves(const JointSamples& s,
                                          const Eigen::MatrixXd& rigid_prediction,
                                          const Eigen::MatrixXd& abs_gravity,
                                          const StribeckParametersX& linear, bool fit_load,
                                          int samples_per_joint, const FrictionCurves& judged,
                                          const Eigen::MatrixXd* coupling) {
  return friction_curves(s, rigid_prediction, abs_gravity, linear, fit_load, samples_per_joint,
                         &judged, coupling)
      .parameters;
}

LinearNominal linear_nominal(const ModelX& model, const EffectDesign& design,
                             const BaseParameters& base, const Eigen::VectorXd& theta) {
  LinearNominal out;
  out.nominal.model = model;
  out.nominal.resize(model.joint_count());
  out.linear.resize(model.joint_count());
  out.nominal.base_count = base.size();
  out.rigid_theta = Eigen::VectorXd::Zero(design.features());
  using Friction = JointFrictionColumns;
  for (const FeatureGroup& g : design.groups()) {
    if (g.key == RigidBodyColumns::key) {
      for (int i = 0; i < base.size(); ++i) {
        out.nominal.base_columns[i] = base.independent[i];
        out.nominal.base_values[i] = theta[g.columns[i]];
        out.rigid_theta[g.columns[i]] = theta[g.columns[i]];
      }
    } else if (g.key == Friction::key) {
      out.linear.coulomb[g.joint] = out.linear.static_friction[g.joint] =
          theta[g.columns[Friction::kCoulomb]];
      out.linear.viscous[g.joint] = theta[g.columns[Friction::kViscous]];
    } else if (g.key == MotorFrictionColumns::key) {  // coupled motors: after their joints'
      for (int m = 0; m < model.joint_count(); ++m)
        if (motor_is_coupled(model, m)) {
          out.linear.coulomb[m] = out.linear.static_friction[m] =
              theta[g.columns[2 * m + MotorFrictionColumns::kCoulomb]];
          out.linear.viscous[m] = theta[g.columns[2 * m + MotorFrictionColumns::kViscous]];
        }
    }
  }
  return out;
}

namespace {

// What the friction curves are fitted against: the rigid prediction, or with
// friction_from_sensor effort − (τ_sensor + I_a·q̈) where the joint's sensor varies (its linear
// start then from the same target, kept in `from_sensor`): `rigid` itself, not a copy, or
// `from_sensor`.
const Eigen::MatrixXd& friction_reference(const Log& log, const JointSamples& s,
                                          const Eigen::MatrixXd& rigid,
                                          const IdentifyOptions& options, LinearNominal& fit,
                                          std::vector<std::string>& notes,
                                          Eigen::MatrixXd& from_sensor) {
  if (!options.friction_from_sensor) return rigid;
  const int n = s.joints();
  // I_a of each joint: the base value of column "Ia<j>" where it is a base column of its own.
  Eigen::VectorXd armature = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < fit.nominal.base_count; ++i)
    if (fit.nominal.base_columns[i] >= 10 * n && fit.nominal.base_columns[i] < 11 * n)
      armature[fit.nominal.base_columns[i] - 10 * n] = fit.nominal.base_values[i];
  SensorFrictionReference sensor = sensor_friction_reference(log, s, armature, rigid);
  for (int j = 0; j < n; ++j)
    if (sensor.from_sensor[j] && std::isfinite(sensor.coulomb[j])) {
      fit.linear.coulomb[j] = fit.linear.static_friction[j] = sensor.coulomb[j];
      fit.linear.viscous[j] = sensor.viscous[j];
    }
  notes.push_back(sensor.note);
  from_sensor = std::move(sensor.reference);
  return from_sensor;
}

}  // namespace

Identification identify(const Log& log, const ModelX& model, const IdentifyOptions& options) {
  return identify(log, model, prepare_identification(log, model, options.samples), options);
}

Identification identify(const Log& log, const ModelX& model, IdentificationSetup setup,
                        const IdentifyOptions& options) {
  auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  const int joints = model.joint_count();
  Identification out;
  out.samples = std::move(setup.samples);
  const JointSamples& s = out.samples;
  const BaseParameters& base = setup.base;

  say("identify: pass 1/3: regressors of " + std::to_string(s.size()) + " samples");
  // A coupled model also reads the motors' friction columns of Y (MotorFrictionColumns).
  const auto regressors =
      setup.regressors && (!model.coupled || setup.regressors->holds(11 * joints))
          ? setup.regressors
          : std::make_shared<const SampleRegressors>(
                model,
                EffectDesign::regressor_columns(joints, base.independent, false, model.coupled), s);
  const EffectDesign design(model, base, s, regressors, {},
                            options.samples.regimes.static_velocity);
  const DesignGrams grams = design.accumulate(s);
  FitSelection selection;
  selection.regimes = {false, true, true};  // moving samples only
  std::vector<int> columns;
  for (const FeatureGroup& g : design.groups())
    if (g.key == RigidBodyColumns::key)
      columns.insert(columns.end(), g.columns.begin(), g.columns.end());
    else if (g.key == JointFrictionColumns::key && !motor_is_coupled(model, g.joint))
      // the sliding levels, not the friction at rest
      columns.insert(columns.end(), g.columns.begin(), g.columns.begin() + 2);
    else if (g.key == MotorFrictionColumns::key)  // a coupled motor's, on every joint it drives
      for (int m = 0; m < joints; ++m)
        if (motor_is_coupled(model, m))
          columns.insert(columns.end(), g.columns.begin() + 2 * m, g.columns.begin() + 2 * m + 2);
  Eigen::VectorXd theta = fit_columns(grams, columns, selection);
  out.joint_weights = moving_residual_weights(grams, theta);
  selection.joint_weights = out.joint_weights;

  say("identify: pass 2/3: rigid-body prediction, friction curves (Ceres)");
  // Judged on the held-out rows, the model is then refitted on every row for the file.
  out.refitted = holds_rows_out(s);
  FitSelection every = selection;
  every.heldout_rows = true;
  const RobotFileInertiaPrior prior = options.inertia_prior
                                          ? robot_file_inertia_prior(model, design, base)
                                          : RobotFileInertiaPrior{};
  const RobotFileInertiaPrior* inertia_prior = options.inertia_prior ? &prior : nullptr;
  PriorFit judged =
      choose_inertia_prior(model, design, base, grams, columns, selection, inertia_prior);
  PriorFit written = out.refitted ? refit_with_inertia_prior(model, design, base, grams, columns,
                                                             every, inertia_prior, judged)
                                  : judged;
  out.inertia_prior = {options.inertia_prior,
                       judged.strength,
                       written.strength,
                       judged.min_eigenvalue_without,
                       written.min_eigenvalue_without,
                       prior.floor,
                       judged.candidates,
                       judged.choice};
  LinearNominal fit = std::move(judged.fit);
  LinearNominal final_fit = std::move(written.fit);
  std::vector<Eigen::MatrixXd> rigids = design.predict_each(
      s, out.refitted ? std::vector<Eigen::VectorXd>{fit.rigid_theta, final_fit.rigid_theta}
                      : std::vector<Eigen::VectorXd>{fit.rigid_theta});
  const Eigen::MatrixXd& rigid = rigids.front();
  Eigen::MatrixXd computed_load;  // |G(q)| unless prepare_diagnosis computed it for both
  if (!setup.abs_gravity) computed_load = gravity_load(model, s);
  const Eigen::MatrixXd& load = setup.abs_gravity ? *setup.abs_gravity : computed_load;
  out.judged_linear = fit.linear;  // on the effort, before a sensor's friction replaces it
  out.fit_load_friction = options.fit_load_friction;
  out.friction_samples_per_joint = options.friction_samples_per_joint;
  Eigen::MatrixXd sensor_reference;
  const Eigen::MatrixXd& reference =
      friction_reference(log, s, rigid, options, fit, out.friction_notes, sensor_reference);
  const Eigen::MatrixXd* coupling = model.coupled ? &model.coupling : nullptr;
  const FrictionCurves curves =
      fit_friction_curves(s, reference, load, fit.linear, options.fit_load_friction,
                          options.friction_samples_per_joint, coupling);
  out.friction_notes.insert(out.friction_notes.end(), curves.notes.begin(), curves.notes.end());
  NominalModelX nominal = fit.nominal;
  nominal.friction = curves.parameters;
  const StribeckParametersX& linear = fit.linear;
  out.nominal = out.judged = nominal;
  if (out.refitted) {
    std::vector<std::string> unused;
    Eigen::MatrixXd final_sensor_reference;
    const Eigen::MatrixXd& final_reference = friction_reference(
        log, s, rigids.back(), options, final_fit, unused, final_sensor_reference);
    out.nominal = final_fit.nominal;
    out.nominal.friction =
        refit_friction_curves(s, final_reference, load, final_fit.linear, options.fit_load_friction,
                              options.friction_samples_per_joint, curves, coupling);
  }

  say("identify: pass 3/3: validation on held-out blocks");
  // Same as nominal_residual(nominal, s) (the rigid part is the prediction above, the model has
  // no added effects), without a third regressor pass.
  out.residual.resize(s.size(), joints);
  parallel_halves(s.size(), [&](Eigen::Index begin, Eigen::Index end) {
    Eigen::VectorXd abs_g(joints);  // sized once, assigned per sample
    for (Eigen::Index k = begin; k < end; ++k) {
      if (!s.valid[k]) {
        out.residual.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      for (int j = 0; j < joints; ++j)
        abs_g[j] = load(k, j);  // element-wise: no resize path (GCC 12 warns on Eigen's)
      if (model.coupled) {      // motor m's curve on (C·q̇)_m, through Cᵀ
        Eigen::VectorXd dq = s.dq.row(k).transpose(), friction = Eigen::VectorXd::Zero(joints);
        for (int m = 0; m < joints; ++m) {
          const double v = model.motor_rate(m, dq);
          model.add_motor_torque(m,
                                 stribeck_friction(nominal.friction, m, v, abs_g[m]) +
                                     neighbour_load_friction(nominal.friction, m, v, abs_g),
                                 friction);
        }
        for (int j = 0; j < joints; ++j)
          out.residual(k, j) = s.effort(k, j) - rigid(k, j) - friction[j];
        continue;
      }
      // stribeck_friction of every joint, term by term without a vector per sample.
      for (int j = 0; j < joints; ++j) {
        const double dq = s.dq(k, j);
        const double friction = stribeck_friction(nominal.friction, j, dq, abs_g[j]) +
                                neighbour_load_friction(nominal.friction, j, dq, abs_g);
        out.residual(k, j) = s.effort(k, j) - rigid(k, j) - friction;
      }
    }
  });
  parallel_jobs(2, [&](int split) {
    (split == 0 ? out.heldout : out.training) = split_regime_stats(s, out.residual, split == 0);
  });
  out.consistency = check_consistency(out.nominal);
  if (!(out.consistency.min_mass_eigenvalue > 0) && !options.inertia_prior)
    out.consistency.problems.front() +=  // check_consistency's M(q) problem
        "; or, for a physical M(q) from this log, identify again without --no-inertia-prior "
        "(IdentifyOptions::inertia_prior: the rigid body pulled toward the robot file's "
        "inertias just as far as M(q) needs, docs/identification.md)";
  if (!(out.consistency.min_mass_eigenvalue > 0) && s.ddq.cwiseAbs().maxCoeff() == 0.0)
    out.consistency.problems.push_back(
        "every acceleration of the log is zero (its ddq<j> columns?): the inertias are not "
        "excited, so M(q) cannot be identified; drop the ddq<j> columns to let the tools derive "
        "them from dq<j>, or log a motion that accelerates");
  for (int j = 0; j < joints; ++j)
    if (linear.coulomb[j] < 0 || linear.viscous[j] < 0) {
      char text[320];
      std::snprintf(text, sizeof text,
                    "joint %d: the linear least squares gave Coulomb %.4g N*m and viscous %.4g "
                    "N*m*s/rad: "
                    "friction cannot push the motion, so the effort does not follow sgn(q̇) and "
                    "q̇ as the model has them (an offset, a direction asymmetry or a delay can do "
                    "this: run tpf diagnose); the curve is fitted from 0",
                    j + 1, linear.coulomb[j], linear.viscous[j]);
      out.consistency.problems.push_back(text);
    }
  return out;
}

}  // namespace tpf::offline
