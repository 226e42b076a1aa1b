// Per-joint held-out error in motion of a residual, for tests comparing a fit with a reference
// fit on the same held-out rows.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

#include "offline/samples/joint_samples.hpp"

namespace tpf::test {

/// Sample k of joint j is valid and neither static nor invalid (static-to-kinetic or moving).
inline bool moving_sample(const offline::JointSamples& s, int j, Eigen::Index k) {
  return s.valid[k] && s.regimes[j][k] != offline::Regime::Static &&
         s.regimes[j][k] != offline::Regime::Invalid;
}

/// Per joint: the RMS of `residual` over the held-out moving samples where it is finite, and how
/// many samples that is.
struct HeldOutMovingRms {
  Eigen::VectorXd rms;
  Eigen::VectorXi samples;
};

inline HeldOutMovingRms heldout_moving_rms(const offline::JointSamples& s,
                                           const Eigen::MatrixXd& residual) {
  const int joints = static_cast<int>(residual.cols());
  HeldOutMovingRms out{Eigen::VectorXd::Zero(joints), Eigen::VectorXi::Zero(joints)};
  for (int j = 0; j < joints; ++j) {
    double sse = 0;
    int n = 0;
    for (Eigen::Index k = 0; k < s.size(); ++k)
      if (s.heldout[k] && moving_sample(s, j, k) && std::isfinite(residual(k, j))) {
        sse += residual(k, j) * residual(k, j);
        ++n;
      }
    out.rms[j] = std::sqrt(sse / std::max(n, 1));
    out.samples[j] = n;
  }
  return out;
}

}  // namespace tpf::test
