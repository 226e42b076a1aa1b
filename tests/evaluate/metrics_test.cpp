// Evaluation metrics on hand-made sequences with known answers.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "offline/evaluate/contact_detection.hpp"
#include "offline/evaluate/force_error.hpp"
#include "offline/evaluate/residual_table.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

constexpr double kRate = 400.0;

/// Two joints, 400 rows at rest then 400 rows moving at 0.1 rad/s. Joint j: nominal residual
/// 10(j+1) at rest and 20(j+1) moving; compensated 1 at rest, 4 for the first `meet` moving rows,
/// then equal to the nominal one (the residuals meet there).
ResidualRecording recording(int meet) {
  ResidualRecording r;
  const int T = 800;
  r.t = Eigen::VectorXd::LinSpaced(T, 0.0, (T - 1) / kRate);
  r.dq = Eigen::MatrixXd::Zero(T, 2);
  r.nominal.resize(T, 2);
  r.compensated.resize(T, 2);
  for (int k = 0; k < T; ++k) {
    for (int j = 0; j < 2; ++j) {
      const bool moving = k >= 400;
      r.dq(k, j) = moving ? 0.1 : 0.0;
      r.nominal(k, j) = (moving ? 20.0 : 10.0) * (j + 1);
      r.compensated(k, j) = !moving ? 1.0 : (k < 400 + meet ? 4.0 : r.nominal(k, j));
    }
  }
  return r;
}

const ResidualRow& row(const std::vector<ResidualRow>& rows, int joint, Regime regime) {
  for (const ResidualRow& r : rows)
    if (r.joint == joint && r.regime == regime) return r;
  throw Error("row not found");
}

TEST(ResidualTable, KnownResidualGivesKnownRmsePerRegime) {
  const int meet = 28;  // 70 ms at 400 Hz
  const auto rows = residual_table({recording(meet)}, Eigen::Vector2d(0.5, 0.5));
  for (int j = 0; j < 2; ++j) {
    const ResidualRow& s = row(rows, j, Regime::Static);
    EXPECT_EQ(s.nominal.count, 400u);
    EXPECT_NEAR(s.nominal.rmse, 10.0 * (j + 1), 1e-12);
    EXPECT_NEAR(s.compensated.rmse, 1.0, 1e-12);
    EXPECT_NEAR(s.compensated.std, 0.0, 1e-12);
    const ResidualRow& k = row(rows, j, Regime::StaticToKinetic);
    EXPECT_EQ(k.nominal.count, static_cast<std::size_t>(meet));
    EXPECT_NEAR(k.nominal.rmse, 20.0 * (j + 1), 1e-12);
    EXPECT_NEAR(k.compensated.rmse, 4.0, 1e-12);
    EXPECT_EQ(row(rows, j, Regime::Moving).nominal.count, static_cast<std::size_t>(400 - meet));
  }
  // Pooled: static nominal RMSE = √((10² + 20²)/2).
  const ResidualRow& all = row(rows, -1, Regime::Static);
  EXPECT_EQ(all.nominal.count, 800u);
  EXPECT_NEAR(all.nominal.rmse, std::sqrt(250.0), 1e-12);
  EXPECT_NEAR(percent_change(all.nominal.rmse, all.compensated.rmse),
              100.0 * (1.0 / std::sqrt(250.0) - 1.0), 1e-9);
}

TEST(ResidualTable, RecordingsArePooledAndSizesChecked) {
  const auto rows = residual_table({recording(10), recording(30)}, Eigen::Vector2d(0.5, 0.5));
  EXPECT_EQ(row(rows, 0, Regime::StaticToKinetic).nominal.count, 40u);
  ResidualRecording bad = recording(10);
  bad.nominal.conservativeResize(10, 2);
  EXPECT_THROW(residual_table({bad}, Eigen::Vector2d(0.5, 0.5)), Error);
}

TEST(ContactDetection, KnownLatencyMissAndFalseAlarm) {
  const int T = 1000;
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(T, 0.0, (T - 1) / kRate);
  Eigen::VectorXd contact = Eigen::VectorXd::Zero(T);
  Eigen::MatrixXd force = Eigen::MatrixXd::Zero(T, 3);
  for (int k = 100; k <= 300; ++k) {  // event 1: a ramp to 8 N along y
    contact[k] = 3;
    force(k, 1) = 8.0 * std::min(1.0, (k - 100) / 40.0);
  }
  for (int k = 500; k <= 520; ++k) {  // event 2: 1.5 N, never detected
    contact[k] = 5;
    force(k, 2) = -1.5;
  }
  Eigen::VectorXi detected = Eigen::VectorXi::Zero(T);
  detected.segment(112, 250).setOnes();  // 30 ms late, holds on past the release
  detected[900] = 1;                     // one false alarm
  const auto events = contact_events(contact, force);
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].first, 100);
  EXPECT_EQ(events[0].last, 300);
  EXPECT_DOUBLE_EQ(events[0].peak_force, 8.0);
  const DetectionStats s = detection_stats(t, events, force, detected, 0.5);
  EXPECT_EQ(s.events, 2);
  EXPECT_EQ(s.detected, 1);
  EXPECT_NEAR(s.median_latency_s, 12.0 / kRate, 1e-12);
  EXPECT_NEAR(s.median_force_n, 8.0 * 12.0 / 40.0, 1e-12);
  EXPECT_DOUBLE_EQ(s.smallest_detected_peak_n, 8.0);
  EXPECT_DOUBLE_EQ(s.largest_missed_peak_n, 1.5);
  // Free rows: all but [100, 300 + 200] and [500, 520 + 200] (0.5 s settle = 200 rows).
  const double free_rows = T - (401 + 220);
  EXPECT_NEAR(s.false_alarm_share, 1.0 / free_rows, 1e-12);  // row 900
  Eigen::VectorXi late = Eigen::VectorXi::Zero(T);
  late[450] = 1;  // inside the settle time of event 1: not an alarm
  EXPECT_EQ(detection_stats(t, events, force, late, 0.5).false_alarm_share, 0.0);
}

TEST(ForceError, KnownRotationAndScale) {
  const int T = 20;
  Eigen::MatrixXd truth(T, 3), estimate(T, 3);
  const double angle = 10.0 * std::numbers::pi / 180.0;
  for (int k = 0; k < T; ++k) {
    const Eigen::Vector3d f(1.0 + k, 0.0, -2.0);
    truth.row(k) = f.transpose();
    const Eigen::Vector3d g = 1.1 * (Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()) * f);
    estimate.row(k) = g.transpose();
  }
  std::vector<Eigen::Index> rows;
  for (int k = 0; k < T; ++k)
    rows.push_back(k);
  const ForceErrorStats s = force_error(estimate, truth, rows);
  EXPECT_EQ(s.count, static_cast<std::size_t>(T));
  double sq = 0;
  for (int k = 0; k < T; ++k) {
    EXPECT_NEAR(s.magnitude_error[k], 0.1 * truth.row(k).norm(), 1e-12);
    sq += std::pow(0.1 * truth.row(k).norm(), 2);
  }
  EXPECT_NEAR(s.magnitude_rmse, std::sqrt(sq / T), 1e-12);
  // The rotation is about z and f has a z part: the angle to the true force is below 10°.
  EXPECT_GT(s.median_angle_deg, 0.0);
  EXPECT_LT(s.p90_angle_deg, 10.0 + 1e-9);
  const ForceErrorStats same = force_error(truth, truth, rows);
  EXPECT_NEAR(same.median_angle_deg, 0.0, 1e-6);
  EXPECT_NEAR(same.vector_rmse, 0.0, 1e-12);
}

}  // namespace
}  // namespace tpf::offline
