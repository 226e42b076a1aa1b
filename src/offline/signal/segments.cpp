#include "offline/signal/segments.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tpf/common/error.hpp"

namespace tpf::offline {

double median_step(const Eigen::VectorXd& t) {
  std::vector<double> steps;
  steps.reserve(static_cast<std::size_t>(std::max<Eigen::Index>(t.size() - 1, 0)));
  for (Eigen::Index k = 1; k < t.size(); ++k)
    if (std::isfinite(t[k]) && std::isfinite(t[k - 1])) steps.push_back(t[k] - t[k - 1]);
  if (steps.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  return *middle;
}

std::vector<Segment> contiguous_segments(const Eigen::VectorXd& t, const Eigen::VectorXd& x,
                                         double gap_factor) {
  if (x.size() != 0 && x.size() != t.size())
    throw Error("contiguous_segments: t has " + std::to_string(t.size()) + " samples, x has " +
                std::to_string(x.size()));
  return contiguous_segments(t, x, gap_factor, median_step(t));
}

std::vector<Segment> contiguous_segments(const Eigen::VectorXd& t, const Eigen::VectorXd& x,
                                         double gap_factor, double median_step_s) {
  if (x.size() != 0 && x.size() != t.size())
    throw Error("contiguous_segments: t has " + std::to_string(t.size()) + " samples, x has " +
                std::to_string(x.size()));
  const double max_step = gap_factor * median_step_s;
  const auto valid = [&](Eigen::Index k) {
    return std::isfinite(t[k]) && (x.size() == 0 || std::isfinite(x[k]));
  };
  std::vector<Segment> segments;
  Eigen::Index k = 0;
  while (k < t.size()) {
    if (!valid(k)) {
      ++k;
      continue;
    }
    Segment segment{k, k + 1};
    while (segment.end < t.size() && valid(segment.end) &&
           !(t[segment.end] - t[segment.end - 1] > max_step))
      ++segment.end;
    segments.push_back(segment);
    k = segment.end;
  }
  return segments;
}

}  // namespace tpf::offline
