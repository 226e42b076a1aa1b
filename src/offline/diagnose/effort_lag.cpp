#include "offline/diagnose/effort_lag.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "offline/signal/segments.hpp"

namespace tpf::offline {
namespace {

/// p at t_k − lag by linear interpolation within k's stretch [start, end); NaN outside it.
/// `steps`: lag in median steps, where the search starts.
double lagged_value(const Eigen::VectorXd& t, const Eigen::VectorXd& p, Eigen::Index k,
                    Eigen::Index start, Eigen::Index end, double lag, Eigen::Index steps) {
  const double at = t[k] - lag;
  if (at < t[start] || at > t[end - 1]) return std::nan("");
  Eigen::Index i = std::clamp<Eigen::Index>(k - steps, start, end - 1);
  while (i > start && t[i] > at)
    --i;
  while (i + 1 < end && t[i + 1] <= at)
    ++i;
  if (i + 1 >= end || t[i + 1] == t[i]) return p[i];
  const double w = (at - t[i]) / (t[i + 1] - t[i]);
  return (1 - w) * p[i] + w * p[i + 1];
}

struct Stretches {
  std::vector<Eigen::Index> start, end;
};

Stretches stretches_of(const Eigen::VectorXd& t, double step) {
  Stretches out;
  out.start.assign(static_cast<std::size_t>(t.size()), 0);
  out.end.assign(static_cast<std::size_t>(t.size()), 0);
  for (const Segment& seg : contiguous_segments(t, Eigen::VectorXd(), 1.5, step))
    for (Eigen::Index k = seg.begin; k < seg.end; ++k) {
      out.start[static_cast<std::size_t>(k)] = seg.begin;
      out.end[static_cast<std::size_t>(k)] = seg.end;
    }
  return out;
}

/// (p(t_k) − p(t_k − lag))/lag, lag = steps median steps; 0 where it is not defined.
double difference_quotient(const Eigen::VectorXd& t, const Eigen::VectorXd& p, Eigen::Index k,
                           const Stretches& st, double lag, Eigen::Index steps) {
  const auto i = static_cast<std::size_t>(k);
  const double lagged = lagged_value(t, p, k, st.start[i], st.end[i], lag, steps);
  const double value = (p[k] - lagged) / lag;
  return std::isfinite(value) ? value : 0.0;
}

}  // namespace

EffortLag search_effort_lag(const JointSamples& s, const Eigen::MatrixXd& prediction,
                            const Eigen::MatrixXd& residual, double max_lag_s) {
  const int joints = static_cast<int>(prediction.cols());
  EffortLag out;
  out.column = Eigen::MatrixXd::Zero(s.size(), joints);
  const double step = median_step(s.t);
  if (!(step > 0) || s.size() < 2) return out;
  const Stretches st = stretches_of(s.t, step);
  std::vector<std::vector<Eigen::Index>> rows(static_cast<std::size_t>(joints));
  Eigen::VectorXd energy = Eigen::VectorXd::Zero(joints);
  for (int j = 0; j < joints; ++j) {
    for (Eigen::Index k : moving_training_rows(s, j, 20000))
      if (std::isfinite(residual(k, j))) {
        rows[static_cast<std::size_t>(j)].push_back(k);
        energy[j] += residual(k, j) * residual(k, j);
      }
  }
  std::vector<Eigen::VectorXd> columns;  // copied once: a column block is no VectorXd
  for (int j = 0; j < joints; ++j)
    columns.emplace_back(prediction.col(j));
  const int most = std::clamp(static_cast<int>(std::lround(max_lag_s / step)), 3, 250);
  double best = 0.0;
  for (int steps = -most; steps <= most; ++steps) {
    if (steps == 0) continue;
    const double lag = steps * step;
    double score = 0.0;
    for (int j = 0; j < joints; ++j) {
      if (!(energy[j] > 0)) continue;
      double rx = 0, xx = 0;
      for (Eigen::Index k : rows[static_cast<std::size_t>(j)]) {
        const double x =
            difference_quotient(s.t, columns[static_cast<std::size_t>(j)], k, st, lag, steps);
        rx += residual(k, j) * x;
        xx += x * x;
      }
      if (xx > 0) score += rx * rx / xx / energy[j];
    }
    if (score > best) {
      best = score;
      out.lag_s = lag;
    }
  }
  out.explained = best;
  if (out.lag_s == 0.0) return out;
  const auto best_steps = static_cast<Eigen::Index>(std::lround(out.lag_s / step));
  for (int j = 0; j < joints; ++j)
    for (Eigen::Index k = 0; k < s.size(); ++k)
      out.column(k, j) = difference_quotient(s.t, columns[static_cast<std::size_t>(j)], k, st,
                                             out.lag_s, best_steps);
  return out;
}

}  // namespace tpf::offline
