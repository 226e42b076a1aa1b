#include "offline/diagnose/cad_payload_check.hpp"

#include <algorithm>
#include <cmath>

#include "offline/diagnose/column_geometry.hpp"
#include "offline/diagnose/effect_selection.hpp"
#include "offline/effects/effect_columns.hpp"

namespace tpf::offline {
namespace {

/// A group's columns fitted on motion: all but the friction held at rest (zero in motion).
std::vector<int> moving_columns(const FeatureGroup& g) {
  std::vector<int> c;
  for (std::size_t i = 0; i < g.columns.size(); ++i)
    if (static_cast<int>(i) != g.held_column) c.push_back(g.columns[i]);
  return c;
}

std::vector<int> concatenated(std::vector<int> a, const std::vector<int>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

/// The payload fitted beside `beside` (the rigid body held at the robot file's values).
struct PayloadFit {
  double improvement = 0.0;  ///< fraction of the weighted held-out moving SSE removed
  double bic_change = 0.0;
  double mass = 0.0, mass_standard_error = 0.0;
  Eigen::VectorXd theta;  ///< with the payload
  bool passes(const DiagnoseOptions& o) const {
    return improvement >= o.min_improvement && bic_change < 0 && mass > 0 &&
           mass >= o.min_standard_errors * mass_standard_error;
  }
};

class PayloadJudge {
 public:
  PayloadJudge(const DesignGrams& grams, const Eigen::VectorXd& cad, const FitSelection& selection,
               double inflation)
      : grams_(grams),
        cad_(cad),
        selection_(selection),
        inflation_(inflation),
        A_(training_gram(grams, selection)) {}

  PayloadFit fit(const std::vector<int>& beside, const std::vector<int>& payload) const {
    const std::vector<int> with_payload = concatenated(beside, payload);
    const Eigen::VectorXd without = refit_columns(grams_, beside, cad_, selection_);
    PayloadFit f;
    f.theta = refit_columns(grams_, with_payload, cad_, selection_);
    const auto [sse0, n] = heldout_sse(heldout_table(grams_, without), -1, w());
    const auto [sse1, n1] = heldout_sse(heldout_table(grams_, f.theta), -1, w());
    f.improvement = sse0 > 0 ? 1.0 - sse1 / sse0 : 0.0;
    f.bic_change = n * std::log(std::max(sse1, 1e-300) / std::max(sse0, 1e-300)) +
                   static_cast<double>(payload.size()) * std::log(std::max(n, 2.0));
    f.mass = f.theta[payload[0]];
    f.mass_standard_error = mass_standard_error(f.theta, beside, payload);
    return f;
  }

  /// cos² of the smallest principal angle between the payload's columns and `effect`'s, outside
  /// `beside`.
  double shared(const std::vector<int>& beside, const std::vector<int>& payload,
                const std::vector<int>& effect) const {
    return shared_share(A_, beside, payload, effect);
  }

 private:
  const Eigen::VectorXd& w() const { return selection_.joint_weights; }

  /// Standard error of the mass: σ̂² (weighted training SSE/(n − p), inflated for the residual's
  /// autocorrelation) times the mass's diagonal element of the inverse of the payload's Gram
  /// with `beside` projected out (equilibrated: mass and inertia columns differ in scale).
  double mass_standard_error(const Eigen::VectorXd& theta, const std::vector<int>& beside,
                             const std::vector<int>& payload) const {
    double sse = 0, count = 0;
    for (int j = 0; j < grams_.joints; ++j)
      for (int r = 0; r < DesignGrams::kRegimes; ++r)
        if (selection_.regimes[r]) {
          const ResidualSums sums = residual_sums(grams_, theta, j, r, 0);
          sse += (w().size() ? w()[j] : 1.0) * sums.sum_squares;
          count += sums.count;
        }
    const double parameters = static_cast<double>(beside.size() + payload.size());
    const double sigma2 = sse / std::max(count - parameters, 1.0) * inflation_;
    const Eigen::MatrixXd S = projected_gram(A_, beside, payload);
    Eigen::VectorXd d(S.rows());
    for (Eigen::Index i = 0; i < d.size(); ++i)
      d[i] = S(i, i) > 0 ? 1.0 / std::sqrt(S(i, i)) : 0.0;
    const Eigen::MatrixXd inverse = d.asDiagonal() *
                                    symmetric_power(d.asDiagonal() * S * d.asDiagonal(), -1.0) *
                                    d.asDiagonal();
    return std::sqrt(std::max(sigma2 * inverse(0, 0), 0.0));
  }

  const DesignGrams& grams_;
  const Eigen::VectorXd& cad_;
  const FitSelection& selection_;
  double inflation_;
  const Eigen::MatrixXd A_;
};

}  // namespace

CadPayloadCheck judge_cad_payload(const DesignGrams& grams, const std::vector<FeatureGroup>& groups,
                                  const Eigen::VectorXd& cad, const std::vector<int>& selected,
                                  const std::vector<TransferFold>& transfer,
                                  const FitSelection& selection,
                                  const Eigen::VectorXd& variance_inflation,
                                  const DiagnoseOptions& options) {
  std::vector<int> friction, payload;
  for (const FeatureGroup& g : groups) {
    if (g.key == JointFrictionColumns::key) friction = concatenated(friction, moving_columns(g));
    // A coupled model's: its motors' friction on their velocities (repeats rank-safe)
    if (g.key == MotorFrictionColumns::key) friction = concatenated(friction, g.columns);
    if (g.key == PayloadColumns::key) payload = g.columns;
  }
  std::vector<int> effects;
  for (int g : selected)
    effects = concatenated(effects, moving_columns(groups[g]));
  const PayloadJudge judge(grams, cad, selection,
                           variance_inflation.size() ? variance_inflation.maxCoeff() : 1.0);
  const PayloadFit fit = judge.fit(concatenated(friction, effects), payload);
  CadPayloadCheck c;
  c.improvement = fit.improvement;
  c.bic_change = fit.bic_change;
  c.mass = fit.mass;
  c.mass_standard_error = fit.mass_standard_error;
  if (c.mass > 0)
    c.centre =
        Vector3<double>(fit.theta[payload[1]], fit.theta[payload[2]], fit.theta[payload[3]]) /
        c.mass;
  // A payload is the arm's: it must lower the held-out error of every file held out in turn.
  for (const TransferFold& fold : transfer) {
    const PayloadFit other =
        PayloadJudge(fold.grams, cad, selection, 1.0).fit(concatenated(friction, effects), payload);
    if (!(other.improvement >= c.transfer_improvement)) {
      c.transfer_improvement = other.improvement;
      c.transfer_file = fold.file;
    }
  }
  const bool transfers =
      std::isnan(c.transfer_improvement) || c.transfer_improvement >= options.min_improvement;
  c.claimed = fit.passes(options) && transfers;
  if (fit.passes(options)) return c;
  // Not beyond the selected effects: "ambiguous" with each selected effect that, left out,
  // frees a payload that passes, and whose columns the payload's nearly span.
  for (int g : selected) {
    std::vector<int> others = friction;
    for (int e : selected)
      if (e != g) others = concatenated(others, moving_columns(groups[e]));
    const std::vector<int> own = moving_columns(groups[g]);
    const double shared = judge.shared(others, payload, own);
    if (judge.fit(others, payload).passes(options) && shared >= options.max_shared_share) {
      c.ambiguous_with.push_back(g);
      c.ambiguous_shares.push_back(shared);
    }
  }
  return c;
}

}  // namespace tpf::offline
