#include "offline/log/derived_rates.hpp"

#include "offline/common/not_a_number.hpp"
#include "offline/signal/acceleration.hpp"
#include "offline/signal/segments.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {

DerivedRates derive_rates(const Eigen::VectorXd& t, const Eigen::VectorXd& q, double cutoff_hz) {
  if (t.size() != q.size())
    throw Error("derive_rates: t has " + std::to_string(t.size()) + " samples, q " +
                std::to_string(q.size()));
  const double step = median_step(t);
  const Eigen::VectorXd v = zero_phase_low_pass(t, q, cutoff_hz, step);
  DerivedRates out{Eigen::VectorXd::Constant(q.size(), kNaN),
                   Eigen::VectorXd::Constant(q.size(), kNaN)};
  for (const Segment& s : contiguous_segments(t, v, 1.5, step))
    for (Eigen::Index k = s.begin + 1; k + 1 < s.end; ++k) {
      const double before = t[k] - t[k - 1];
      const double after = t[k + 1] - t[k];
      out.velocity[k] = (v[k + 1] - v[k - 1]) / (before + after);
      out.acceleration[k] =
          2.0 * ((v[k + 1] - v[k]) / after - (v[k] - v[k - 1]) / before) / (before + after);
    }
  return out;
}

}  // namespace tpf::offline
