#include "offline/diagnose/diagnose.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

#include "offline/identify/identification_setup.hpp"
#include "offline/signal/acceleration.hpp"
#include "tpf/common/error.hpp"
#include "tpf/dynamics/regressor.hpp"

namespace tpf::offline {
namespace {

// Held-out residual table of θ from the Gram matrices.
RegimeTable heldout_table(const DesignGrams& grams, const Eigen::VectorXd& theta) {
  RegimeTable table(grams.joints);
  for (int j = 0; j < grams.joints; ++j)
    for (int r = 0; r < DesignGrams::kRegimes; ++r) {
      table[j][r] = residual_sums(grams, theta, j, r, 1);
      table[j][3] += table[j][r];
    }
  return table;
}

// Held-out SSE and count over the joints a group acts on (all joints weighted when global).
std::pair<double, double> heldout_sse(const RegimeTable& t, int joint, const Eigen::VectorXd& w) {
  double sse = 0, count = 0;
  for (int j = 0; j < static_cast<int>(t.size()); ++j)
    if (joint < 0 || joint == j) {
      // Moving samples only (static-to-kinetic and moving): at rest the effort holds whatever
      // friction the motion left (memory), which would only add history noise to the score.
      for (int r = 1; r < DesignGrams::kRegimes; ++r) {
        sse += (joint < 0 ? w[j] : 1.0) * t[j][r].sum_squares;
        count += t[j][r].count;
      }
    }
  return {sse, count};
}

// The integer n in [lo, hi] whose sin/cos of n·scale·q best explains r (periodogram).
double dominant_cycles(const Eigen::VectorXd& q, const Eigen::VectorXd& r, int lo, int hi,
                       double scale) {
  double best = 0, best_power = -1;
  for (int n = lo; n <= hi; ++n) {
    std::complex<double> sum = 0;
    for (Eigen::Index k = 0; k < q.size(); ++k)
      sum += r[k] * std::polar(1.0, -n * scale * q[k]);
    if (std::norm(sum) > best_power) {
      best_power = std::norm(sum);
      best = n;
    }
  }
  return best;
}

std::string format(const char* fmt, double a, double b = 0, double c = 0) {
  char text[256];
  std::snprintf(text, sizeof text, fmt, a, b, c);
  return text;
}

}  // namespace

template <int N>
Diagnosis<N> diagnose(const Log& log, const Model<double, N>& model,
                      const DiagnoseOptions& options) {
  auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  Diagnosis<N> out;
  IdentificationSetup<N> setup = prepare_identification(log, model, options.samples);
  out.samples = std::move(setup.samples);
  const JointSamples& s = out.samples;
  const JointVector<double, N>& scale = setup.effort_scale;
  const BaseParameters& base = setup.base;
  const double threshold = options.samples.regimes.static_velocity;
  FitSelection selection;  // fit on moving samples: friction at rest has memory
  selection.regimes = {false, true, true};

  // 1. The declared model alone.
  say("diagnose: pass 1/4: declared model");
  const EffectDesign<N> declared(model, base, scale, s, {}, threshold);
  // A first fit for the candidates' inputs (weights, ripple periods, prediction rate): every
  // 4th sample is plenty; selection and the before/after table use every sample (pass 3).
  const DesignGrams grams0 = declared.accumulate(s, 4);
  Eigen::VectorXd theta0 = fit_columns(grams0, declared.declared_columns(), selection);
  Eigen::VectorXd weights(N);
  for (int j = 0; j < N; ++j) {
    ResidualSums sums;
    for (int r = 1; r < DesignGrams::kRegimes; ++r)
      sums += residual_sums(grams0, theta0, j, r, 0);
    weights[j] = 1.0 / std::max(sums.std() * sums.std(), 1e-18);
  }
  selection.joint_weights = weights;
  theta0 = fit_columns(grams0, declared.declared_columns(), selection);

  // 2. Residual of the declared model: noise floor, ripple periods, prediction rate.
  say("diagnose: pass 2/4: residual analysis");
  // The delay candidate shifts the rigid-body part (smooth); the friction's own lag at a reversal
  // is friction memory, not a delay of the drive.
  Eigen::VectorXd rigid0 = Eigen::VectorXd::Zero(theta0.size());
  for (const FeatureGroup& g : declared.groups())
    if (g.kind == FeatureKind::Rigid)
      for (int c : g.columns)
        rigid0[c] = theta0[c];
  const std::vector<Eigen::MatrixXd> predictions0 = declared.predict_each(s, {theta0, rigid0});
  const Eigen::MatrixXd& rigid_prediction0 = predictions0[1];
  const Eigen::MatrixXd residual0 = s.effort - predictions0[0];  // declared, fitted on motion
  out.noise_floor.resize(N);
  CandidateInputs inputs;
  inputs.enabled = true;
  inputs.ripple_cycles.resize(N);
  inputs.ripple_motor_cycles.resize(N);
  inputs.prediction_rate.resize(s.size(), N);
  inputs.abs_gravity = gravity_load(model, s);
  inputs.reference_temperature =
      s.temperature.cols() == N
          ? s.temperature.col(0).array().isFinite().select(s.temperature.col(0).array(), 0).mean()
          : 25.0;
  for (int j = 0; j < N; ++j) {
    double sum = 0, count = 0;
    std::vector<Eigen::Index> moving;
    for (Eigen::Index k = 1; k < s.size(); ++k) {
      if (s.valid[k] && s.valid[k - 1] && s.regimes[j][k] == Regime::Static &&
          s.regimes[j][k - 1] == Regime::Static) {
        sum += std::pow(s.effort(k, j) - s.effort(k - 1, j), 2);
        ++count;
      }
      if (s.valid[k] && !s.heldout[k] && s.regimes[j][k] == Regime::Moving) moving.push_back(k);
    }
    out.noise_floor[j] = count > 0 ? std::sqrt(sum / count / 2.0) : std::nan("");
    const std::size_t stride = std::max<std::size_t>(1, moving.size() / 20000);
    const Eigen::Index m = static_cast<Eigen::Index>(moving.size() / stride);
    Eigen::VectorXd q(m), r(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      q[i] = s.q(moving[i * stride], j);
      r[i] = residual0(moving[i * stride], j);
    }
    inputs.ripple_cycles[j] = m > 100 ? dominant_cycles(q, r, 3, 64, 1.0) : 0.0;
    inputs.ripple_motor_cycles[j] =
        m > 100 ? dominant_cycles(q, r, 1, 4, model.gear_ratio[j]) : 0.0;
    inputs.prediction_rate.col(j) = derive_acceleration(s.t, rigid_prediction0.col(j), 15.0);
  }
  if (s.temperature.cols() != N)
    out.notes.push_back("temperature-dependent friction not checked: the log has no temp<j>");
  if (N == 1) out.notes.push_back("coupling between joints not checked: one joint");

  // 3. The library of candidates on the same samples.
  say("diagnose: pass 3/4: candidate effects");
  const EffectDesign<N> design(model, base, scale, s, inputs, threshold);
  const DesignGrams grams = design.accumulate(s);
  out.groups = design.groups();
  std::vector<int> columns = design.declared_columns();
  // The friction held at rest (last direction of motion × level, and × |G| once load-dependent
  // friction is selected) is fitted on the static training samples on top of the model fitted
  // on motion, which it leaves unchanged.
  FitSelection at_rest = selection;
  at_rest.regimes = {true, false, false};
  auto with_held_friction = [&](const Eigen::VectorXd& moving_theta, const std::vector<int>& used) {
    std::vector<int> held;
    for (const FeatureGroup& g : design.groups())
      if ((g.kind == FeatureKind::Friction || g.kind == FeatureKind::LoadFriction) &&
          std::find(used.begin(), used.end(), g.columns[2]) != used.end())
        held.push_back(g.columns[2]);
    return refit_columns(grams, held, moving_theta, at_rest);
  };
  Eigen::VectorXd theta = fit_columns(grams, columns, selection);
  const Eigen::VectorXd theta_before = with_held_friction(theta, columns);
  out.before = heldout_table(grams, theta_before);
  std::vector<bool> used(out.groups.size(), false);
  for (int round = 1; round <= options.max_effects; ++round) {
    int best = -1;
    double best_gain = 0;
    CandidateTrial best_trial;
    for (std::size_t g = 0; g < out.groups.size(); ++g) {
      const FeatureGroup& group = out.groups[g];
      if (group.declared || used[g]) continue;
      std::vector<int> trial_columns = columns;
      trial_columns.insert(trial_columns.end(), group.columns.begin(), group.columns.end());
      const Eigen::VectorXd trial_theta = fit_columns(grams, trial_columns, selection);
      const RegimeTable now = heldout_table(grams, theta);
      const RegimeTable with = heldout_table(grams, trial_theta);
      const auto [sse0, n] = heldout_sse(now, group.joint, weights);
      const auto [sse1, n1] = heldout_sse(with, group.joint, weights);
      CandidateTrial trial{group.key, group.title, group.joint, round, 0, 0, false};
      trial.improvement = sse0 > 0 ? 1.0 - sse1 / sse0 : 0.0;
      trial.bic_change = n * std::log(std::max(sse1, 1e-300) / std::max(sse0, 1e-300)) +
                         static_cast<double>(group.columns.size()) * std::log(std::max(n, 2.0));
      out.trials.push_back(trial);
      if (trial.improvement >= options.min_improvement && trial.bic_change < 0 &&
          trial.improvement > best_gain) {
        best = static_cast<int>(g);
        best_gain = trial.improvement;
      }
    }
    if (best < 0) break;
    used[best] = true;
    out.selected.push_back(best);
    for (CandidateTrial& t : out.trials)
      if (t.round == round && t.title == out.groups[best].title) t.selected = true;
    columns.insert(columns.end(), out.groups[best].columns.begin(), out.groups[best].columns.end());
    theta = fit_columns(grams, columns, selection);
  }
  theta = with_held_friction(theta, columns);
  out.after = heldout_table(grams, theta);

  // 4. Residual after, the effect terms, and the extended nominal model.
  say("diagnose: pass 4/4: refit with the selected effects");
  // One pass for the declared and the extended model, each selected effect's term and the
  // non-friction part.
  std::vector<Eigen::VectorXd> thetas{theta, theta_before};
  for (int g : out.selected) {
    Eigen::VectorXd part = Eigen::VectorXd::Zero(design.features());
    for (int c : out.groups[g].columns)
      part[c] = theta[c];
    thetas.push_back(part);
  }
  Eigen::VectorXd non_friction = theta;
  for (const FeatureGroup& g : out.groups)
    if (g.kind == FeatureKind::Friction || g.kind == FeatureKind::LoadFriction ||
        g.kind == FeatureKind::Thermal)
      for (int c : g.columns)
        non_friction[c] = 0.0;
  thetas.push_back(non_friction);
  std::vector<Eigen::MatrixXd> predictions = design.predict_each(s, thetas);
  out.residual_after = s.effort - predictions[0];
  out.residual_before = s.effort - predictions[1];
  for (std::size_t e = 0; e < out.selected.size(); ++e)
    out.effect_terms.push_back(std::move(predictions[e + 2]));
  const Eigen::MatrixXd& rigid_prediction = predictions.back();

  NominalModel<double, N>& nominal = out.nominal;
  nominal.model = model;
  nominal.effort_unit = s.effort_unit;
  nominal.effort_per_newton_metre = scale;
  nominal.base_count = base.size();
  Eigen::VectorXd payload = Eigen::VectorXd::Zero(11 * N);
  StribeckParameters<double, N> linear;
  bool load_selected = false;
  for (const FeatureGroup& g : out.groups) {
    const int j = g.joint;
    auto value = [&](int i) { return theta[g.columns[i]]; };
    if (g.kind == FeatureKind::Rigid) {
      for (int i = 0; i < base.size(); ++i)
        nominal.base_columns[i] = base.independent[i];
    } else if (g.kind == FeatureKind::Friction) {
      linear.coulomb[j] = linear.static_friction[j] = std::max(value(0), 0.0);
      linear.viscous[j] = std::max(value(1), 0.0);
    } else if (g.kind == FeatureKind::Payload) {
      for (int i = 0; i < 10; ++i)
        payload[10 * (N - 1) + i] = value(i);
    } else if (g.kind == FeatureKind::LoadFriction) {
      linear.load_coulomb[j] = std::max(value(0), 0.0);
      linear.load_viscous[j] = std::max(value(1), 0.0);
      load_selected = load_selected || value(0) != 0.0 || value(1) != 0.0;
    } else if (g.kind == FeatureKind::Ripple || g.kind == FeatureKind::RippleMotor) {
      if (value(0) == 0.0 && value(1) == 0.0) continue;
      RippleTerm<double>& t = nominal.added.ripple[nominal.added.ripple_count++];
      t.joint = j;
      t.motor_side = g.kind == FeatureKind::RippleMotor;
      t.cycles_per_rev = t.motor_side ? inputs.ripple_motor_cycles[j] : inputs.ripple_cycles[j];
      t.sin_amplitude = value(0);
      t.cos_amplitude = value(1);
    } else if (g.kind == FeatureKind::Thermal) {
      nominal.added.thermal_viscous[j] = value(0);
      nominal.added.reference_temperature = inputs.reference_temperature;
    } else if (g.kind == FeatureKind::Spring) {
      nominal.added.spring_stiffness[j] = value(0);
      nominal.added.spring_offset[j] = value(1);
    } else if (g.kind == FeatureKind::Delay) {
      if (value(0) != 0.0) nominal.added.effort_lead_s = value(0);
    } else if (g.kind == FeatureKind::Coupling) {
      int i = 0;
      for (int k = 0; k < N; ++k)
        if (k != j) {
          nominal.added.coupling_velocity(j, k) = value(i++);
          nominal.added.coupling_acceleration(j, k) = value(i++);
        }
    }
  }
  const Eigen::VectorXd payload_base = base.project(payload);
  for (const FeatureGroup& g : out.groups)
    if (g.kind == FeatureKind::Rigid)
      for (int i = 0; i < base.size(); ++i)
        nominal.base_values[i] = theta[g.columns[i]] + payload_base[i];
  Eigen::VectorXd sigma(N);
  for (int j = 0; j < N; ++j)
    sigma[j] = 1.0 / std::sqrt(weights[j]);
  nominal.friction = fit_friction_curves<N>(s, rigid_prediction, inputs.abs_gravity, linear,
                                            load_selected, 20000, sigma);

  // A payload against the robot file's inertias (CAD).
  {
    const Eigen::VectorXd cad_values = base.project(
        dynamic_parameters(model, JointVector<double, N>::Zero(), JointVector<double, N>::Zero())
            .head(11 * N));
    Eigen::VectorXd cad = Eigen::VectorXd::Zero(design.features());
    std::vector<int> friction_columns, payload_columns;
    for (const FeatureGroup& g : out.groups) {
      if (g.kind == FeatureKind::Rigid)
        for (int i = 0; i < base.size(); ++i)
          cad[g.columns[i]] = cad_values[i];
      if (g.kind == FeatureKind::Friction)
        friction_columns.insert(friction_columns.end(), g.columns.begin(), g.columns.begin() + 2);
      if (g.kind == FeatureKind::Payload) payload_columns = g.columns;
    }
    std::vector<int> with_payload = friction_columns;
    with_payload.insert(with_payload.end(), payload_columns.begin(), payload_columns.end());
    const Eigen::VectorXd without = refit_columns(grams, friction_columns, cad, selection);
    const Eigen::VectorXd with = refit_columns(grams, with_payload, cad, selection);
    const auto [sse0, n] = heldout_sse(heldout_table(grams, without), -1, weights);
    const auto [sse1, n1] = heldout_sse(heldout_table(grams, with), -1, weights);
    CadPayloadCheck& c = out.cad_payload;
    c.improvement = sse0 > 0 ? 1.0 - sse1 / sse0 : 0.0;
    c.bic_change = n * std::log(std::max(sse1, 1e-300) / std::max(sse0, 1e-300)) +
                   10.0 * std::log(std::max(n, 2.0));
    c.mass = with[payload_columns[0]];
    if (c.mass > 0)
      c.centre = Vector3<double>(with[payload_columns[1]], with[payload_columns[2]],
                                 with[payload_columns[3]]) /
                 c.mass;
    c.claimed = c.improvement >= options.min_improvement && c.bic_change < 0 && c.mass > 0;
  }

  // Findings in plain words.
  if (out.cad_payload.claimed)
    out.findings.push_back(
        format("Against the robot file's inertias: a payload of %.3g kg on the last link",
               out.cad_payload.mass) +
        format(" at (%.3f, %.3f, %.3f) m in its frame", out.cad_payload.centre.x(),
               out.cad_payload.centre.y(), out.cad_payload.centre.z()) +
        format(" — removes %.1f %% of the held-out residual sum of squares of the CAD model "
               "(absorbed by the identified rigid body, so not a missing effect of the "
               "identified model).",
               100 * out.cad_payload.improvement));
  if (out.selected.empty())
    out.findings.push_back(
        "No candidate effect lowers the held-out residual enough to be claimed (threshold " +
        format("%.0f %%", 100 * options.min_improvement) + " of the residual sum of squares).");
  for (int g : out.selected) {
    for (const CandidateTrial& t : out.trials)
      if (t.selected && t.title == out.groups[g].title)
        out.findings.push_back(
            "Found: " + t.title +
            format(" — removes %.1f %% of the held-out residual sum of squares (BIC change %.0f).",
                   100 * t.improvement, t.bic_change));
  }
  for (int j = 0; j < N; ++j) {
    const double moving = out.after[j][2].rmse();
    const double still = out.after[j][0].rmse();
    const double floor = out.noise_floor[j];
    if (std::isfinite(floor) && moving > 3 * floor)
      out.findings.push_back(
          "Left unexplained on joint " + std::to_string(j + 1) +
          format(": moving held-out RMSE %.3g is %.1f× the noise floor at rest (%.3g); no "
                 "candidate of the library explains the rest.",
                 moving, moving / floor, floor));
    if (std::isfinite(floor) && still > 3 * floor)
      out.findings.push_back(
          "Left unexplained on joint " + std::to_string(j + 1) +
          format(": static held-out RMSE %.3g is %.1f× the noise floor (%.3g): the friction held "
                 "at rest depends on the history of the motion (memory), which no memoryless "
                 "effect explains (the TCN compensator's job).",
                 still, still / floor, floor));
  }
  return out;
}

template Diagnosis<1> diagnose<1>(const Log&, const Model<double, 1>&, const DiagnoseOptions&);
template Diagnosis<2> diagnose<2>(const Log&, const Model<double, 2>&, const DiagnoseOptions&);
template Diagnosis<3> diagnose<3>(const Log&, const Model<double, 3>&, const DiagnoseOptions&);
template Diagnosis<4> diagnose<4>(const Log&, const Model<double, 4>&, const DiagnoseOptions&);
template Diagnosis<5> diagnose<5>(const Log&, const Model<double, 5>&, const DiagnoseOptions&);
template Diagnosis<6> diagnose<6>(const Log&, const Model<double, 6>&, const DiagnoseOptions&);
template Diagnosis<7> diagnose<7>(const Log&, const Model<double, 7>&, const DiagnoseOptions&);

}  // namespace tpf::offline
