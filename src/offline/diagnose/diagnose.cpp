#include "offline/diagnose/diagnose.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>

#include "offline/identify/identification_setup.hpp"
#include "offline/regimes/regime.hpp"
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

// Σ_j w_j Σ_(selected regimes) of the training Grams: [φ; y; 1] over every joint row.
Eigen::MatrixXd training_gram(const DesignGrams& grams, const FitSelection& selection) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(grams.features + 2, grams.features + 2);
  for (int j = 0; j < grams.joints; ++j)
    for (int r = 0; r < DesignGrams::kRegimes; ++r)
      if (selection.regimes[r])
        A +=
            (selection.joint_weights.size() ? selection.joint_weights[j] : 1.0) * grams.at(j, r, 0);
  return A;
}

Eigen::MatrixXd block(const Eigen::MatrixXd& A, const std::vector<int>& rows,
                      const std::vector<int>& cols) {
  Eigen::MatrixXd out(rows.size(), cols.size());
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < cols.size(); ++c)
      out(r, c) = A(rows[r], cols[c]);
  return out;
}

// X^(−1/2) (power −½ of a symmetric PSD matrix; directions with no energy map to 0) or, with
// power −1, the pseudo-inverse.
Eigen::MatrixXd symmetric_power(const Eigen::MatrixXd& X, double power) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (X + X.transpose()));
  Eigen::VectorXd d = eig.eigenvalues();
  const double tol = 1e-12 * std::max(d.cwiseAbs().maxCoeff(), 1e-300);
  for (Eigen::Index i = 0; i < d.size(); ++i)
    d[i] = d[i] > tol ? std::pow(d[i], power) : 0.0;
  return eig.eigenvectors() * d.asDiagonal() * eig.eigenvectors().transpose();
}

// Schur complement A_CC − A_CM A_MM⁺ A_MC: the Gram of C's columns with M's span projected out.
Eigen::MatrixXd projected_gram(const Eigen::MatrixXd& A, const std::vector<int>& model,
                               const std::vector<int>& c) {
  if (model.empty()) return block(A, c, c);
  // Equilibrate M before the pseudo-inverse (columns of very different scales).
  Eigen::MatrixXd amm = block(A, model, model);
  Eigen::VectorXd d(amm.rows());
  for (Eigen::Index i = 0; i < d.size(); ++i)
    d[i] = amm(i, i) > 0 ? 1.0 / std::sqrt(amm(i, i)) : 0.0;
  const Eigen::MatrixXd inv = d.asDiagonal() *
                              symmetric_power(d.asDiagonal() * amm * d.asDiagonal(), -1.0) *
                              d.asDiagonal();
  const Eigen::MatrixXd acm = block(A, c, model);
  return block(A, c, c) - acm * inv * acm.transpose();
}

// sin² of the smallest principal angle between span(c) and span(model) on the data.
double distinct_share(const Eigen::MatrixXd& A, const std::vector<int>& model,
                      const std::vector<int>& c) {
  const Eigen::MatrixXd r = symmetric_power(block(A, c, c), -0.5);
  const Eigen::MatrixXd share = r * projected_gram(A, model, c) * r;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (share + share.transpose()));
  return std::clamp(eig.eigenvalues().minCoeff(), 0.0, 1.0);
}

// cos² of the smallest principal angle between the parts of span(b) and span(c) outside
// span(model).
double shared_share(const Eigen::MatrixXd& A, const std::vector<int>& model,
                    const std::vector<int>& b, const std::vector<int>& c) {
  std::vector<int> both = b;
  both.insert(both.end(), c.begin(), c.end());
  const Eigen::MatrixXd S = projected_gram(A, model, both);
  const Eigen::Index nb = static_cast<Eigen::Index>(b.size());
  const Eigen::Index nc = static_cast<Eigen::Index>(c.size());
  const Eigen::MatrixXd rb = symmetric_power(S.topLeftCorner(nb, nb), -0.5);
  const Eigen::MatrixXd rc = symmetric_power(S.bottomRightCorner(nc, nc), -0.5);
  const Eigen::MatrixXd cross = rb * S.topRightCorner(nb, nc) * rc;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(cross);
  const double top = svd.singularValues().size() ? svd.singularValues()[0] : 0.0;
  return std::clamp(top * top, 0.0, 1.0);
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
  Eigen::VectorXd inflation = Eigen::VectorXd::Ones(N);
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
    // A period must fit in the motion, or the sine cannot be told from an offset or a slope.
    double range = 0;
    if (m > 100) {
      std::vector<double> sorted(q.data(), q.data() + m);
      std::sort(sorted.begin(), sorted.end());
      range = sorted[static_cast<std::size_t>(0.99 * (m - 1))] -
              sorted[static_cast<std::size_t>(0.01 * (m - 1))];
    }
    const int shortest = std::max(3, static_cast<int>(std::ceil(2 * M_PI / std::max(range, 1e-9))));
    inputs.ripple_cycles[j] =
        m > 100 && shortest <= 64 ? dominant_cycles(q, r, shortest, 64, 1.0) : 0.0;
    if (m > 100 && shortest > 3)
      out.notes.push_back("joint " + std::to_string(j + 1) +
                          format(": moves over %.2f rad, so position ripple is checked only from "
                                 "%.0f periods/rev (a longer period does not fit in the motion)",
                                 range, shortest));
    // Lag-1 autocorrelation of the residual on motion: the samples are not independent, which
    // inflates the variance of every coefficient by (1 + ρ)/(1 − ρ).
    double num = 0, den = 0;
    for (std::size_t i = 1; i < moving.size(); ++i)
      if (moving[i] == moving[i - 1] + 1) {
        num += residual0(moving[i], j) * residual0(moving[i - 1], j);
        den += residual0(moving[i], j) * residual0(moving[i], j);
      }
    const double rho = den > 0 ? std::clamp(num / den, 0.0, 0.995) : 0.0;
    inflation[j] = (1 + rho) / (1 - rho);
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
  const Eigen::VectorXd theta_declared = theta;
  std::vector<bool> used(out.groups.size(), false);
  const Eigen::MatrixXd A = training_gram(grams, selection);
  const int P = design.features();
  // The groups in the model so far (declared first), for naming what a candidate is collinear to.
  std::vector<int> in_model;
  for (std::size_t g = 0; g < out.groups.size(); ++g)
    if (out.groups[g].declared) in_model.push_back(static_cast<int>(g));
  // A column with (numerically) nothing in it on the training rows, e.g. |G_k| of a joint whose
  // axis is vertical (rounding noise of 1e-16), is left out: its coefficient would be anything.
  auto alive = [&](int col) { return A(col, col) > 1e-20 * A(P + 1, P + 1); };
  auto model_columns = [&](int except) {
    std::vector<int> c;
    for (int g : in_model)
      if (g != except)
        for (int col : out.groups[g].columns)
          if (alive(col)) c.push_back(col);
    return c;
  };
  auto energetic = [&](const FeatureGroup& group) {
    std::vector<int> c;
    for (int col : group.columns)
      if (alive(col)) c.push_back(col);
    return c;
  };
  for (int round = 1; round <= options.max_effects; ++round) {
    const std::vector<int> model = model_columns(-1);
    std::vector<int> eligible;
    std::vector<double> gain(out.groups.size(), 0.0);
    for (std::size_t g = 0; g < out.groups.size(); ++g) {
      const FeatureGroup& group = out.groups[g];
      if (group.declared || used[g]) continue;
      const std::vector<int> own = energetic(group);
      if (own.empty()) continue;
      // A periodic effect must explain what an offset and a slope of its joint cannot: it is
      // judged on top of them (over a short range a sine is one or the other).
      std::vector<int> reference = columns;
      std::vector<int> reference_model = model;
      if (group.kind == FeatureKind::Ripple || group.kind == FeatureKind::RippleMotor)
        for (const FeatureGroup& other : out.groups)
          if (other.joint == group.joint &&
              (other.kind == FeatureKind::Offset || other.kind == FeatureKind::Spring))
            for (int c : other.columns)
              if (std::find(reference.begin(), reference.end(), c) == reference.end()) {
                reference.push_back(c);
                if (alive(c)) reference_model.push_back(c);
              }
      std::vector<int> trial_columns = reference;
      trial_columns.insert(trial_columns.end(), own.begin(), own.end());
      const Eigen::VectorXd trial_theta = fit_columns(grams, trial_columns, selection);
      const RegimeTable now = heldout_table(grams, reference.size() == columns.size()
                                                       ? theta
                                                       : fit_columns(grams, reference, selection));
      const RegimeTable with = heldout_table(grams, trial_theta);
      const auto [sse0, n] = heldout_sse(now, group.joint, weights);
      const auto [sse1, n1] = heldout_sse(with, group.joint, weights);
      CandidateTrial trial{group.key, group.title, group.joint, round, 0, 0, 0, 1, false};
      trial.improvement = sse0 > 0 ? 1.0 - sse1 / sse0 : 0.0;
      trial.bic_change = n * std::log(std::max(sse1, 1e-300) / std::max(sse0, 1e-300)) +
                         static_cast<double>(group.columns.size()) * std::log(std::max(n, 2.0));
      // Standard errors from the training fit: σ̂² = weighted SSE/(n − p), inflated for the
      // residual's autocorrelation; the group's Wald distance from zero.
      double sse_train = 0, count = 0;
      for (int j = 0; j < N; ++j)
        for (int r = 0; r < DesignGrams::kRegimes; ++r)
          if (selection.regimes[r]) {
            const ResidualSums sums = residual_sums(grams, trial_theta, j, r, 0);
            sse_train += weights[j] * sums.sum_squares;
            count += sums.count;
          }
      const double sigma2 = sse_train / std::max(count - trial_columns.size(), 1.0) *
                            (group.joint >= 0 ? inflation[group.joint] : inflation.maxCoeff());
      const Eigen::MatrixXd S = projected_gram(A, reference_model, own);
      Eigen::VectorXd th(own.size());
      for (std::size_t i = 0; i < own.size(); ++i)
        th[static_cast<Eigen::Index>(i)] = trial_theta[own[i]];
      trial.wald = std::sqrt(std::max(th.dot(S * th), 0.0) / std::max(sigma2, 1e-300));
      trial.distinct_share = distinct_share(A, reference_model, own);
      gain[g] = trial.improvement;
      out.trials.push_back(trial);
      if (trial.improvement >= options.min_improvement && trial.bic_change < 0 &&
          trial.wald >= options.min_standard_errors)
        eligible.push_back(static_cast<int>(g));
    }
    if (eligible.empty()) break;
    int best = eligible.front();
    for (int g : eligible)
      if (gain[g] > gain[best]) best = g;
    // An effect of every joint (one shared delay) is preferred to the same effect on one joint
    // when both pass: the per-joint one would leave the others for spurious companions.
    for (int g : eligible)
      if (out.groups[g].key == out.groups[best].key && out.groups[g].joint == -1 &&
          out.groups[best].joint >= 0)
        best = g;
    Claim claim;
    claim.groups.push_back(best);
    claim.improvements.push_back(gain[best]);
    const std::vector<int> own = energetic(out.groups[best]);
    // Candidates that explain the same thing: their parts outside the model nearly collinear.
    for (int g : eligible) {
      if (g == best) continue;
      const FeatureGroup& other = out.groups[g];
      if (other.joint >= 0 && out.groups[best].joint >= 0 && other.joint != out.groups[best].joint)
        continue;
      if (other.key == out.groups[best].key) continue;  // per-joint vs every-joint of one effect
      if (shared_share(A, model, own, energetic(other)) >= options.max_shared_share) {
        claim.groups.push_back(g);
        claim.improvements.push_back(gain[g]);
      }
    }
    // A candidate the model's own columns nearly span: ambiguous with the model group whose
    // removal frees it most.
    claim.distinct_share = distinct_share(A, model, own);
    if (claim.distinct_share < options.min_distinct_share) {
      int partner = -1;
      double freed = claim.distinct_share;
      for (int g : in_model) {
        const double share = distinct_share(A, model_columns(g), own);
        if (share > freed) {
          freed = share;
          partner = g;
        }
      }
      if (partner >= 0) {
        claim.groups.push_back(partner);
        claim.improvements.push_back(std::nan(""));
      }
    }
    used[best] = true;
    in_model.push_back(best);
    out.selected.push_back(best);
    for (CandidateTrial& t : out.trials)
      if (t.round == round && t.title == out.groups[best].title) t.selected = true;
    columns.insert(columns.end(), out.groups[best].columns.begin(), out.groups[best].columns.end());
    theta = fit_columns(grams, columns, selection);
    // Coefficients and standard errors on the model it joined.
    {
      const std::vector<int> rest = model_columns(best);
      const Eigen::MatrixXd S = projected_gram(A, rest, own);
      double sse_train = 0, count = 0;
      for (int j = 0; j < N; ++j)
        for (int r = 0; r < DesignGrams::kRegimes; ++r)
          if (selection.regimes[r]) {
            const ResidualSums sums = residual_sums(grams, theta, j, r, 0);
            sse_train += weights[j] * sums.sum_squares;
            count += sums.count;
          }
      const int jb = out.groups[best].joint;
      const double sigma2 = sse_train / std::max(count - columns.size(), 1.0) *
                            (jb >= 0 ? inflation[jb] : inflation.maxCoeff());
      const Eigen::MatrixXd cov = sigma2 * symmetric_power(S, -1.0);
      for (std::size_t i = 0; i < own.size(); ++i) {
        claim.coefficients.push_back(theta[own[i]]);
        claim.standard_errors.push_back(std::sqrt(std::max(cov(i, i), 0.0)));
      }
    }
    // Written only when the run time evaluates it and its coefficients mean something: one that
    // cannot be told from the declared model (the spring k = 217 beside mx = 18.8) is
    // reported, not written.
    const FeatureKind kind = out.groups[best].kind;
    bool beside_declared = false;
    for (int g : claim.groups)
      beside_declared = beside_declared || out.groups[g].declared;
    claim.written = kind != FeatureKind::Delay && kind != FeatureKind::Thermal && !beside_declared;
    out.claims.push_back(std::move(claim));
  }
  theta = with_held_friction(theta, columns);
  out.after = heldout_table(grams, theta);
  // The model written: the selected effects without those not written, refitted (so that the
  // declared parameters are not the ones fitted beside an effect that is left out).
  std::vector<int> written_columns = design.declared_columns();
  for (std::size_t e = 0; e < out.claims.size(); ++e)
    if (out.claims[e].written)
      for (int c : energetic(out.groups[out.selected[e]]))
        written_columns.push_back(c);
  const Eigen::VectorXd theta_selected = theta;
  theta = with_held_friction(fit_columns(grams, written_columns, selection), written_columns);

  // 4. Residual after, the effect terms, and the extended nominal model.
  say("diagnose: pass 4/4: refit with the selected effects");
  // One pass for the declared and the extended model, each selected effect's term and the
  // non-friction part.
  std::vector<Eigen::VectorXd> thetas{theta_selected, theta_before};
  for (std::size_t e = 0; e < out.selected.size(); ++e) {
    // A written effect's term as the written model holds it; the others as selected.
    const Eigen::VectorXd& from = out.claims[e].written ? theta : theta_selected;
    Eigen::VectorXd part = Eigen::VectorXd::Zero(design.features());
    for (int c : out.groups[out.selected[e]].columns)
      part[c] = from[c];
    thetas.push_back(part);
  }
  // The rigid part the friction curves are fitted against: everything written outside the
  // friction (rigid body, payload, ripple, spring, offset, coupling).
  Eigen::VectorXd non_friction = theta;
  for (const FeatureGroup& g : out.groups)
    if (g.kind == FeatureKind::Friction || g.kind == FeatureKind::LoadFriction ||
        g.kind == FeatureKind::Thermal || g.kind == FeatureKind::Delay ||
        g.kind == FeatureKind::Asymmetry || g.kind == FeatureKind::NeighbourLoad)
      for (int c : g.columns)
        non_friction[c] = 0.0;
  thetas.push_back(non_friction);
  Eigen::VectorXd declared_rigid = Eigen::VectorXd::Zero(design.features());
  for (const FeatureGroup& g : out.groups)
    if (g.kind == FeatureKind::Rigid)
      for (int c : g.columns)
        declared_rigid[c] = theta_declared[c];
  thetas.push_back(declared_rigid);
  std::vector<Eigen::MatrixXd> predictions = design.predict_each(s, thetas);
  const Eigen::MatrixXd declared_rigid_prediction = std::move(predictions.back());
  predictions.pop_back();
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
    } else if (g.kind == FeatureKind::Thermal || g.kind == FeatureKind::Delay) {
      // Not evaluated at run time: reported (claims), not written.
    } else if (g.kind == FeatureKind::Spring) {
      nominal.added.spring_stiffness[j] = value(0);
    } else if (g.kind == FeatureKind::Offset) {
      nominal.added.offset[j] = value(0);
    } else if (g.kind == FeatureKind::Asymmetry) {
      linear.coulomb_asymmetry[j] = value(0);
      linear.viscous_asymmetry[j] = value(1);
    } else if (g.kind == FeatureKind::NeighbourLoad) {
      int i = 0;
      for (int k = 0; k < N; ++k)
        if (k != j) {
          linear.neighbour_load_coulomb(j, k) = value(i++);
          linear.neighbour_load_viscous(j, k) = value(i++);
        }
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
  FrictionCurves<N> curves =
      fit_friction_curves<N>(s, rigid_prediction, inputs.abs_gravity, linear, load_selected, 20000);
  nominal.friction = curves.parameters;
  for (const std::string& note : curves.notes)
    out.notes.push_back("friction curve: " + note);
  // The written models on the held-out samples: the declared model as identify fits it, and the
  // extended one (what --params holds).
  {
    NominalModel<double, N> declared_nominal = nominal;
    declared_nominal.added = AddedEffects<double, N>{};
    StribeckParameters<double, N> declared_linear;
    for (const FeatureGroup& g : out.groups) {
      if (g.kind == FeatureKind::Rigid) {
        for (int i = 0; i < base.size(); ++i)
          declared_nominal.base_values[i] = theta_declared[g.columns[i]];
      } else if (g.kind == FeatureKind::Friction) {
        declared_linear.coulomb[g.joint] = declared_linear.static_friction[g.joint] =
            theta_declared[g.columns[0]];
        declared_linear.viscous[g.joint] = theta_declared[g.columns[1]];
      }
    }
    declared_nominal.friction =
        fit_friction_curves<N>(s, declared_rigid_prediction, inputs.abs_gravity, declared_linear,
                               false, 20000)
            .parameters;
    out.written_before = split_regime_stats(s, nominal_residual(declared_nominal, s), true);
    out.residual_written = nominal_residual(nominal, s);
    out.written_after = split_regime_stats(s, out.residual_written, true);
  }

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
  for (const Claim& c : out.claims) {
    const FeatureGroup& g = out.groups[c.groups[0]];
    std::string coefficients;
    for (std::size_t i = 0; i < c.coefficients.size(); ++i)
      coefficients +=
          (i ? ", " : "") + format("%.4g ± %.2g", c.coefficients[i], c.standard_errors[i]);
    std::string text;
    if (!c.ambiguous()) {
      text = "Found: " + g.title +
             format(
                 " — removes %.1f %% of the held-out residual sum of "
                 "squares; coefficients ",
                 100 * c.improvements[0]) +
             coefficients + " (" + (g.column_names.size() == 1 ? g.column_names[0] : g.key) + ").";
    } else {
      text = "Ambiguous between " + g.title + format(" (removes %.1f %%)", 100 * c.improvements[0]);
      for (std::size_t i = 1; i < c.groups.size(); ++i) {
        const FeatureGroup& other = out.groups[c.groups[i]];
        text += " and " + other.title;
        text += std::isfinite(c.improvements[i])
                    ? format(" (removes %.1f %%)", 100 * c.improvements[i])
                    : std::string(" (declared)");
      }
      text += format(
                  ": on this log their columns are nearly collinear (share outside the model "
                  "%.3f), so the data cannot tell which it is and no coefficient means much "
                  "alone. The model holds the first (",
                  c.distinct_share) +
              coefficients +
              "); a log with more range of motion, both directions and rests tells them apart.";
    }
    if (!c.written && (g.kind == FeatureKind::Delay || g.kind == FeatureKind::Thermal))
      text +=
          " Not written to the parameter file: the run-time nominal model cannot evaluate it "
          "(it keeps no past samples / has no temperature input); the 'written' table "
          "leaves it out.";
    else if (!c.written)
      text +=
          " Not written to the parameter file: it cannot be told from the declared model, "
          "so its coefficients mean nothing there; the written model is refitted without it.";
    out.findings.push_back(text);
  }
  // A regime the written model does worse in than the declared one, explained.
  for (int j = 0; j < N; ++j)
    for (Regime r : {Regime::Static, Regime::StaticToKinetic, Regime::Moving}) {
      const double before = out.written_before[j][r].rmse, after = out.written_after[j][r].rmse;
      if (!(after > 1.02 * before)) continue;
      out.findings.push_back(
          "Joint " + std::to_string(j + 1) + ", " + std::string(regime_name(r)) +
          format(": the written model's held-out RMSE rises from %.4g to %.4g (%+.0f %%). ", before,
                 after, 100 * (after / before - 1)) +
          (r == Regime::Static
               ? "Effects are selected on motion; at rest the effort holds whatever friction the "
                 "motion left (memory) and the run time predicts none, so a term that shifts the "
                 "prediction (offset, spring, load) moves it away from that held friction."
               : "The friction curve refitted with the added effects does worse here than the "
                 "declared model's: the effects and the curve share these samples."));
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
