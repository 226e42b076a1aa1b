#include "offline/regimes/regime_stats.hpp"

#include <cmath>

#include "offline/common/not_a_number.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// Running sums, turned into statistics by a second pass over the same samples.
struct Accumulator {
  std::size_t count = 0;
  double sum = 0.0;
  double sum_sq_dev = 0.0;
  double sum_sq = 0.0;
};

ResidualStats finish(const Accumulator& a) {
  ResidualStats s;
  s.count = a.count;
  if (a.count == 0) {
    s.mean = s.rmse = s.std = kNaN;
    return s;
  }
  const double n = static_cast<double>(a.count);
  s.mean = a.sum / n;
  s.rmse = std::sqrt(a.sum_sq / n);
  s.std = std::sqrt(a.sum_sq_dev / n);
  return s;
}

}  // namespace

RegimeStats regime_stats(const Eigen::VectorXd& residual, const std::vector<Regime>& labels) {
  if (static_cast<std::size_t>(residual.size()) != labels.size())
    throw Error("regime_stats: " + std::to_string(residual.size()) + " residual samples for " +
                std::to_string(labels.size()) + " labels");
  std::array<Accumulator, kRegimeCount> acc{};
  Accumulator all;
  for (Eigen::Index k = 0; k < residual.size(); ++k) {
    const double r = residual[k];
    if (std::isnan(r)) continue;
    const Regime regime = labels[static_cast<std::size_t>(k)];
    for (Accumulator* a :
         {&acc[static_cast<std::size_t>(regime)], regime != Regime::Invalid ? &all : nullptr}) {
      if (a == nullptr) continue;
      ++a->count;
      a->sum += r;
      a->sum_sq += r * r;
    }
  }
  // Second pass: deviations from the mean (numerically safer than sum_sq − n·mean²).
  for (Eigen::Index k = 0; k < residual.size(); ++k) {
    const double r = residual[k];
    if (std::isnan(r)) continue;
    const Regime regime = labels[static_cast<std::size_t>(k)];
    Accumulator& a = acc[static_cast<std::size_t>(regime)];
    const double d = r - a.sum / static_cast<double>(a.count);
    a.sum_sq_dev += d * d;
    if (regime != Regime::Invalid) {
      const double dall = r - all.sum / static_cast<double>(all.count);
      all.sum_sq_dev += dall * dall;
    }
  }
  RegimeStats stats;
  for (int i = 0; i < kRegimeCount; ++i)
    stats.by_regime[static_cast<std::size_t>(i)] = finish(acc[static_cast<std::size_t>(i)]);
  stats.valid = finish(all);
  return stats;
}

double percent_change(double before, double after) {
  if (before == 0.0 || std::isnan(before) || std::isnan(after)) return kNaN;
  return 100.0 * (after - before) / before;
}

}  // namespace tpf::offline
