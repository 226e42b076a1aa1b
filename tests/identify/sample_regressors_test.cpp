// The regressor computed once per log: every entry the design reads is compute_regressor's double.
#include "offline/samples/sample_regressors.hpp"

#include <gtest/gtest.h>

#include <random>

#include "offline/identify/effect_design.hpp"
#include "support/arm_fixture.hpp"
#include "tpf/estimation/nominal_model.hpp"

namespace tpf::test {
namespace {

TEST(SampleRegressors, StoredEntriesAreComputeRegressorsOwn) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  offline::JointSamples s;
  const Eigen::Index n = 50;
  s.t = Eigen::VectorXd::LinSpaced(n, 0.0, 1.0);
  s.q = Eigen::MatrixXd::NullaryExpr(n, kJoints, [&] { return u(rng); });
  s.dq = Eigen::MatrixXd::NullaryExpr(n, kJoints, [&] { return u(rng); });
  s.ddq = Eigen::MatrixXd::NullaryExpr(n, kJoints, [&] { return u(rng); });
  s.valid.assign(n, 1);
  s.valid[7] = 0;  // an invalid sample is skipped
  const Model<double, Eigen::Dynamic> model = joint_count_cast<Eigen::Dynamic>(arm());
  const std::vector<int> base = rigid_body_base_parameters(model).independent;
  const offline::SampleRegressors regressors(
      model, offline::EffectDesign::regressor_columns(kJoints, base, true), s);
  ASSERT_EQ(regressors.size(), n);
  EXPECT_TRUE(regressors.holds(10 * (kJoints - 1)));
  EXPECT_FALSE(regressors.holds(11 * kJoints));  // a friction column no family reads

  ArmData data;
  Regressor<double, kJoints> expected;
  Eigen::MatrixXd loaded = Eigen::MatrixXd::Zero(kJoints, 13 * kJoints);
  for (Eigen::Index k = 0; k < n; ++k) {
    if (!s.valid[k]) continue;
    compute_regressor(arm(), data, s.q.row(k).transpose(), s.dq.row(k).transpose(),
                      s.ddq.row(k).transpose(), expected);
    regressors.load(k, loaded);
    for (int j = 0; j < kJoints; ++j) {
      for (int column : base)
        EXPECT_EQ(loaded(j, column), expected(j, column)) << "sample " << k << " joint " << j;
      for (int p = 0; p < 10; ++p)  // the last link's columns (payload candidate)
        EXPECT_EQ(loaded(j, 10 * (kJoints - 1) + p), expected(j, 10 * (kJoints - 1) + p));
    }
  }
}

TEST(IdentificationColumn, TheColumnsTheFitReadsAndNoOthers) {
  for (const char* name : {"t", "q1", "dq4", "ddq2", "i3", "tau12", "temp1", "tau_sensor7"})
    EXPECT_TRUE(offline::identification_column(name)) << name;
  for (const char* name : {"gt_fric1", "p1", "q", "tau_maker1", "q1x", "1", "tt", "gt_ddq1"})
    EXPECT_FALSE(offline::identification_column(name)) << name;
}

}  // namespace
}  // namespace tpf::test
