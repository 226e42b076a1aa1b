// The share of a held-out error from motion outside the fitting range of q and q̇.
#include "offline/measured_study/coverage_share.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace tpf::offline {
namespace {

JointSamples coverage_samples(const Eigen::VectorXd& q, const Eigen::VectorXd& dq) {
  JointSamples s;
  s.t = Eigen::VectorXd::LinSpaced(q.size(), 0.0, 1.0);
  s.q = q;
  s.dq = dq;
  return s;
}

TEST(CoverageShare, AttributesTheSquaredErrorOfSamplesOutsideTheFittingRange) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Fitting: q̇ from 0 to 1 (one way), q from 0 to 1; a sample at q̇ = −3 has no residual (its
  // file's sensor is flat) and does not widen the range.
  const JointSamples fit =
      coverage_samples(Eigen::Vector4d(0.0, 0.5, 1.0, 2.0), Eigen::Vector4d(0.0, 0.5, 1.0, -3.0));
  const Eigen::MatrixXd fit_residual = Eigen::Vector4d(0.1, 0.1, 0.1, nan);
  // Held out: two samples inside both ranges (residual 1), two moving the other way at q inside
  // (residual 3), one beyond the range of q at a covered q̇ (residual 2), one without residual.
  Eigen::VectorXd q(6), dq(6), r(6);
  q << 0.2, 0.8, 0.5, 0.5, 1.5, 3.0;
  dq << 0.2, 0.8, -0.5, -0.5, 0.5, -5.0;
  r << 1.0, 1.0, 3.0, 3.0, 2.0, nan;
  const CoverageShare c = coverage_share(fit, fit_residual, coverage_samples(q, dq), r);
  EXPECT_DOUBLE_EQ(c.velocity_samples[0], 2.0 / 5.0);
  EXPECT_DOUBLE_EQ(c.velocity_error[0], 18.0 / 24.0);
  EXPECT_DOUBLE_EQ(c.position_samples[0], 1.0 / 5.0);
  EXPECT_DOUBLE_EQ(c.position_error[0], 4.0 / 24.0);
  EXPECT_DOUBLE_EQ(c.fit_velocity_min[0], 0.0);
  EXPECT_DOUBLE_EQ(c.fit_velocity_max[0], 1.0);
}

TEST(CoverageShare, NoFittingResidualGivesNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const JointSamples s = coverage_samples(Eigen::Vector2d(0, 1), Eigen::Vector2d(0, 1));
  const CoverageShare c =
      coverage_share(s, Eigen::Vector2d(nan, nan), s, Eigen::MatrixXd(Eigen::Vector2d(1, 1)));
  EXPECT_TRUE(std::isnan(c.velocity_samples[0]));
  EXPECT_TRUE(std::isnan(c.fit_velocity_min[0]));
}

}  // namespace
}  // namespace tpf::offline
