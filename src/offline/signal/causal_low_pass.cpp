#include "offline/signal/causal_low_pass.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tpf::offline {

Eigen::VectorXd causal_low_pass(const Eigen::VectorXd& t, const Eigen::VectorXd& x, double tau,
                                const std::vector<Eigen::Index>& starts) {
  if (tau <= 0) return x;
  Eigen::VectorXd y(x.size());
  double state = std::numeric_limits<double>::quiet_NaN();
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const bool restart = k == 0 || std::find(starts.begin(), starts.end(), k) != starts.end();
    if (!std::isfinite(x[k])) {
      state = y[k] = x[k];
      continue;
    }
    if (restart || !std::isfinite(state))
      state = x[k];
    else
      state += (1.0 - std::exp(-(t[k] - t[k - 1]) / tau)) * (x[k] - state);
    y[k] = state;
  }
  return y;
}

}  // namespace tpf::offline
