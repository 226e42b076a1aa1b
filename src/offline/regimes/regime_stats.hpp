// Residual statistics per regime: the numbers of the before/after tables.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

#include "offline/regimes/regime.hpp"

namespace tpf::offline {

/// Statistics of the residual r over a set of samples (NaN samples skipped).
struct ResidualStats {
  std::size_t count = 0;  ///< samples used
  double mean = 0.0;      ///< (1/n)·Σ r
  double rmse = 0.0;      ///< √((1/n)·Σ r²)
  double std = 0.0;  ///< √((1/n)·Σ (r − mean)²), population std; rmse² = mean² + std²
};

/// RMSE and std of one joint's residual per regime.
struct RegimeStats {
  std::array<ResidualStats, kRegimeCount>
      by_regime;        ///< indexed by Regime; Invalid counts NaN-label samples
  ResidualStats valid;  ///< all samples that are not Invalid
  const ResidualStats& operator[](Regime r) const { return by_regime[static_cast<std::size_t>(r)]; }
};

/// Per-regime statistics of `residual` (one joint), with `labels` from label_regimes. Samples
/// where the residual is NaN are skipped (and not counted). Empty sets give count 0 and NaN
/// statistics. Throws tpf::Error when sizes differ.
RegimeStats regime_stats(const Eigen::VectorXd& residual, const std::vector<Regime>& labels);

/// Relative change in percent, 100·(after − before)/before (NaN when before is 0 or NaN).
double percent_change(double before, double after);

}  // namespace tpf::offline
