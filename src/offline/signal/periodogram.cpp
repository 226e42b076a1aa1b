#include "offline/signal/periodogram.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

namespace tpf::offline {

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

int shortest_fitting_cycles(double range) {
  // Bounded before the conversion: a joint that barely moves gives 2π/range beyond any int.
  return std::max(3, static_cast<int>(std::min(std::ceil(2 * M_PI / std::max(range, 1e-9)), 1e6)));
}

}  // namespace tpf::offline
