// Contiguous stretches of a sampled signal: no gap in t and no NaN inside.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace tpf::offline {

/// Half-open sample range [begin, end).
struct Segment {
  Eigen::Index begin = 0;
  Eigen::Index end = 0;
  Eigen::Index size() const { return end - begin; }
};

/// Median of t[k+1] − t[k] over steps with finite ends (NaN when there is none).
double median_step(const Eigen::VectorXd& t);

/// Maximal runs of samples where t and x are finite and every step satisfies
/// t[k+1] − t[k] ≤ gap_factor · median_step(t) (a larger step is a gap: dropped cycles).
/// `x` may be empty (then only t is checked). Throws tpf::Error when sizes differ.
std::vector<Segment> contiguous_segments(const Eigen::VectorXd& t, const Eigen::VectorXd& x,
                                         double gap_factor = 1.5);
/// The same with t's median step given (median_step(t), computed once by a caller that needs it
/// for several signals of one t).
std::vector<Segment> contiguous_segments(const Eigen::VectorXd& t, const Eigen::VectorXd& x,
                                         double gap_factor, double median_step_s);

}  // namespace tpf::offline
