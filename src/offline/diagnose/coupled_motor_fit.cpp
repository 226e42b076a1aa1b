#include "offline/diagnose/coupled_motor_fit.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <random>

#include "offline/effects/motor_friction_columns.hpp"
#include "offline/fit/parallel_jobs.hpp"
#include "tpf/dynamics/regressor.hpp"

namespace tpf::offline {
namespace {

/// One training sample of a pair: both joints' velocity, direction, residual and whether each
/// joint's row is moving.
struct PairRow {
  double dq[2], sign[2], r[2];
  bool moving[2];
};

double direction_of(double v, double threshold) {
  return std::abs(v) >= threshold ? (v > 0 ? 1.0 : -1.0) : 0.0;
}

/// The part of pair_sse's normal equations that does not depend on the direction: the Gram of
/// each joint's own Coulomb and viscous columns and of the residual.
struct PairGram {
  Eigen::Matrix4d beside = Eigen::Matrix4d::Zero();  ///< [s_i, q̇_i, s_{i+1}, q̇_{i+1}]
  Eigen::Vector4d target = Eigen::Vector4d::Zero();  ///< their products with the residual
  double residual = 0;                               ///< weighted Σ r²
};

PairGram pair_gram(const std::vector<PairRow>& rows, const double weight[2]) {
  PairGram g;
  for (const PairRow& p : rows)
    for (int j = 0; j < 2; ++j) {
      if (!p.moving[j]) continue;
      const double w = weight[j], s = p.sign[j], v = p.dq[j];
      g.beside(2 * j, 2 * j) += w * s * s;
      g.beside(2 * j, 2 * j + 1) += w * s * v;
      g.beside(2 * j + 1, 2 * j + 1) += w * v * v;
      g.target[2 * j] += w * s * p.r[j];
      g.target[2 * j + 1] += w * v * p.r[j];
      g.residual += w * p.r[j] * p.r[j];
    }
  for (int j = 0; j < 2; ++j)
    g.beside(2 * j + 1, 2 * j) = g.beside(2 * j, 2 * j + 1);
  return g;
}

/// Weighted SSE of the pair's residual after least squares on the motor of direction φ
/// (a = cos φ, b = sin φ) beside each joint's own Coulomb and viscous columns (`fixed`: their
/// part of the normal equations).
double pair_sse(const std::vector<PairRow>& rows, const PairGram& fixed, double phi,
                const double weight[2], double threshold) {
  const double share[2] = {std::cos(phi), std::sin(phi)};
  Eigen::Matrix<double, 6, 6> G = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> h = Eigen::Matrix<double, 6, 1>::Zero();
  for (const PairRow& p : rows) {
    const double rate = share[0] * p.dq[0] + share[1] * p.dq[1];
    const double sign = direction_of(rate, threshold);
    for (int j = 0; j < 2; ++j) {
      if (!p.moving[j]) continue;
      const double w = weight[j], m0 = share[j] * sign, m1 = share[j] * rate;
      G(0, 0) += w * m0 * m0;
      G(1, 0) += w * m1 * m0;
      G(1, 1) += w * m1 * m1;
      G(2 + 2 * j, 0) += w * p.sign[j] * m0;
      G(3 + 2 * j, 0) += w * p.dq[j] * m0;
      G(2 + 2 * j, 1) += w * p.sign[j] * m1;
      G(3 + 2 * j, 1) += w * p.dq[j] * m1;
      h[0] += w * p.r[j] * m0;
      h[1] += w * p.r[j] * m1;
    }
  }
  G.bottomRightCorner<4, 4>() = fixed.beside;
  h.tail<4>() = fixed.target;
  G.triangularView<Eigen::StrictlyUpper>() = G.transpose();
  // Equilibrated, with a tiny ridge: at a joint's own direction the motor's columns repeat it.
  Eigen::Matrix<double, 6, 1> d = G.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  Eigen::Matrix<double, 6, 6> S = d.asDiagonal() * G * d.asDiagonal();
  S.diagonal().array() += 1e-9;
  const Eigen::Matrix<double, 6, 1> hs = d.cwiseProduct(h);
  return fixed.residual - hs.dot(S.ldlt().solve(hs));
}

/// The direction φ of least pair_sse: the grid's best point refined by golden-section search
/// between its neighbours.
double best_direction(const std::vector<PairRow>& rows, const double weight[2], double threshold) {
  const PairGram fixed = pair_gram(rows, weight);
  constexpr int kGrid = 180;
  const double step = std::numbers::pi / kGrid;
  int best = 0;
  double best_sse = std::numeric_limits<double>::infinity();
  for (int g = 0; g < kGrid; ++g) {
    const double sse = pair_sse(rows, fixed, g * step, weight, threshold);
    if (sse < best_sse) {
      best_sse = sse;
      best = g;
    }
  }
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double lo = (best - 1) * step, hi = (best + 1) * step;
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  double f1 = pair_sse(rows, fixed, x1, weight, threshold);
  double f2 = pair_sse(rows, fixed, x2, weight, threshold);
  for (int it = 0; it < 24; ++it) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - ratio * (hi - lo);
      f1 = pair_sse(rows, fixed, x1, weight, threshold);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + ratio * (hi - lo);
      f2 = pair_sse(rows, fixed, x2, weight, threshold);
    }
  }
  return f1 < f2 ? x1 : x2;
}

/// Whether [a; b]·(a q̈_i + b q̈_{i+1}) on joints (i, i + 1) is outside the span of the rigid
/// body's base columns: least squares on regressors at 60 random states.
bool armature_outside_rigid_body(const ModelX& model, const BaseParameters& base, int i, double a,
                                 double b) {
  const int n = model.joint_count();
  constexpr int kStates = 60;
  std::mt19937_64 random(20261129);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::normal_distribution<double> normal(0.0, 1.0);
  DataX data(model);
  Eigen::MatrixXd Y, W(kStates * n, base.size());
  Eigen::VectorXd v = Eigen::VectorXd::Zero(kStates * n);
  Eigen::VectorXd q(n), dq(n), ddq(n);
  for (int k = 0; k < kStates; ++k) {
    for (int j = 0; j < n; ++j) {
      q[j] = model.has_position_limits(j)
                 ? model.lower[j] + (model.upper[j] - model.lower[j]) *
                                        (0.5 + angle(random) / (2 * std::numbers::pi))
                 : angle(random);
      dq[j] = normal(random);
      ddq[j] = normal(random);
    }
    compute_regressor(model, data, q, dq, ddq, Y);
    W.middleRows(k * n, n) = base.reduce(Y);
    const double motor = a * ddq[i] + b * ddq[i + 1];
    v[k * n + i] = a * motor;
    v[k * n + i + 1] = b * motor;
  }
  const Eigen::VectorXd fitted = W * W.colPivHouseholderQr().solve(v);
  return (v - fitted).norm() > 1e-6 * v.norm();
}

}  // namespace

std::vector<CoupledMotorCandidate> fit_coupled_motors(
    const ModelX& model, const BaseParameters& base, const JointSamples& s,
    const Eigen::MatrixXd& residual, const Eigen::VectorXd& weights, double static_velocity) {
  const int n = model.joint_count();
  std::vector<int> pairs;
  for (int i = 0; i + 1 < n; ++i)
    if (!motor_is_coupled(model, i) && !motor_is_coupled(model, i + 1) &&
        model.is_prismatic(i) == model.is_prismatic(i + 1))  // rad and m: no one motor
      pairs.push_back(i);
  // Per pair (two threads): its candidate, or none (too few samples, no coupling found).
  std::vector<std::optional<CoupledMotorCandidate>> found(pairs.size());
  parallel_jobs(static_cast<int>(pairs.size()), [&](int job) {
    const int i = pairs[static_cast<std::size_t>(job)];
    std::vector<PairRow> rows;
    for (Eigen::Index k = 0; k < s.size(); ++k) {
      if (!s.valid[k] || s.heldout[k]) continue;
      PairRow p{};
      bool any = false;
      for (int j = 0; j < 2; ++j) {
        const int joint = i + j;
        const Regime regime = s.regimes[joint][k];
        p.moving[j] = regime != Regime::Static && regime != Regime::Invalid &&
                      std::isfinite(residual(k, joint));
        p.dq[j] = s.dq(k, joint);
        p.sign[j] = direction_of(p.dq[j], static_velocity);
        p.r[j] = p.moving[j] ? residual(k, joint) : 0.0;
        any = any || p.moving[j];
      }
      if (any) rows.push_back(p);
    }
    if (rows.size() < 100) return;
    constexpr std::size_t kRows = 5000;
    if (rows.size() > kRows) {  // every stride-th: the whole log, evenly
      const double stride = static_cast<double>(rows.size()) / kRows;
      for (std::size_t r = 0; r < kRows; ++r)
        rows[r] = rows[static_cast<std::size_t>(static_cast<double>(r) * stride)];
      rows.resize(kRows);
    }
    const double weight[2] = {weights.size() ? weights[i] : 1.0,
                              weights.size() ? weights[i + 1] : 1.0};
    const double phi = best_direction(rows, weight, static_velocity);
    CoupledMotorCandidate m;
    m.joint = i;
    m.static_velocity = static_velocity;
    const double a = std::cos(phi), b = std::sin(phi), scale = std::abs(b) >= std::abs(a) ? b : a;
    m.a = a / scale;
    m.b = b / scale;
    if (!(std::abs(m.ratio()) >= 0.05)) return;
    m.armature = armature_outside_rigid_body(model, base, i, m.a, m.b);
    found[static_cast<std::size_t>(job)] = m;
  });
  std::vector<CoupledMotorCandidate> out;
  for (const auto& m : found)
    if (m) out.push_back(*m);
  return out;
}

}  // namespace tpf::offline
