// Sample extraction runs per joint on two threads and computes t's median step once: its q̈ and
// held sign of motion are those of the one-joint-at-a-time definitions, bit for bit.
#include "offline/samples/joint_samples.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "offline/signal/acceleration.hpp"
#include "offline/signal/segments.hpp"

namespace tpf::offline {
namespace {

constexpr int kSampleJoints = 3;
constexpr int kSampleRows = 2000;

/// Three joints at 100 Hz (jittered), a 1 s gap at row 1200, NaN velocities on joint 2, rests
/// between motions; no ddq<j> columns (derived), currents i<j>.
Log three_joint_log() {
  Log log;
  log.meta.set("rate_hz", "100");
  log.columns = {"t", "q1", "q2", "q3", "dq1", "dq2", "dq3", "i1", "i2", "i3"};
  log.values.resize(kSampleRows, 10);
  for (int k = 0; k < kSampleRows; ++k) {
    const double t = k / 100.0 + 1e-5 * std::sin(7.0 * k) + (k >= 1200 ? 1.0 : 0.0);
    log.values(k, 0) = t;
    for (int j = 0; j < kSampleJoints; ++j) {
      const double w = 0.8 + 0.3 * j;
      const double dq = std::max(0.0, std::abs(std::sin(0.2 * t)) - 0.3) * std::cos(w * t);
      log.values(k, 1 + j) = std::sin(w * t);
      log.values(k, 4 + j) = dq;
      log.values(k, 7 + j) = 100.0 * dq + 10.0 * j;
    }
  }
  for (int k : {300, 301, 1500})
    log.values(k, 5) = std::numeric_limits<double>::quiet_NaN();
  return log;
}

/// The held sign as defined: per segment of t, the sign of the last motion (NaN resets it).
Eigen::MatrixXd held_sign_reference(const JointSamples& s, const SampleOptions& o) {
  Eigen::MatrixXd held = Eigen::MatrixXd::Zero(s.size(), kSampleJoints);
  for (const Segment& seg : contiguous_segments(s.t, {}, o.regimes.gap_factor))
    for (int j = 0; j < kSampleJoints; ++j) {
      double sign = 0.0;
      for (Eigen::Index k = seg.begin; k < seg.end; ++k) {
        const double v = s.dq(k, j);
        if (!std::isfinite(v))
          sign = 0.0;
        else if (std::abs(v) >= o.regimes.static_velocity)
          sign = v > 0 ? 1.0 : -1.0;
        held(k, j) = sign;
      }
    }
  return held;
}

bool same_bits(double a, double b) {
  return a == b || (std::isnan(a) && std::isnan(b));
}

TEST(JointSamples, ParallelExtractionMatchesTheDefinitionsBitForBit) {
  const SampleOptions options;
  const JointSamples s =
      extract_joint_samples(three_joint_log(), Eigen::VectorXd::Ones(kSampleJoints), options);
  ASSERT_EQ(s.size(), kSampleRows);
  const Eigen::MatrixXd held = held_sign_reference(s, options);
  int moving = 0;
  for (int j = 0; j < kSampleJoints; ++j) {
    const Eigen::VectorXd ddq =
        derive_acceleration(s.t, s.dq.col(j), options.acceleration_cutoff_hz);
    for (Eigen::Index k = 0; k < kSampleRows; ++k) {
      ASSERT_TRUE(same_bits(s.ddq(k, j), ddq[k])) << "joint " << j << " row " << k;
      ASSERT_EQ(s.held_sign(k, j), held(k, j)) << "joint " << j << " row " << k;
      moving += held(k, j) != 0.0;
    }
  }
  EXPECT_GT(moving, kSampleRows);  // the held sign is not trivially zero
  // Invalid: the 3 NaN velocities, and q̈ at both ends of every segment (log ends, gap, NaNs):
  // rows 0, 299, 302, 1199, 1200, 1499, 1501, 1999.
  EXPECT_EQ(s.invalid_count, 11u);
}

TEST(JointSamples, AValueNoArmProducesIsSkippedAndCountedApart) {
  // One field of 1e300 (a corrupt current) made every fit NaN: it is skipped like a missing
  // value, and said apart.
  Log log = three_joint_log();
  log.values(700, log.column("i2")) = 1e300;
  const JointSamples s =
      extract_joint_samples(log, Eigen::VectorXd::Ones(kSampleJoints), SampleOptions{});
  EXPECT_EQ(s.invalid_count, 12u);
  EXPECT_EQ(s.out_of_range_count, 1u);
  EXPECT_FALSE(s.valid[700]);
  EXPECT_NE(skipped_samples_text(s).find("11 skipped for a missing value"), std::string::npos);
  EXPECT_NE(skipped_samples_text(s).find("1 for a value beyond ±1e9"), std::string::npos);
}

TEST(JointSamples, ALogShorterThanItsFirstHeldOutBlockSaysNothingIsHeldOut) {
  // Issue 16, "messages that mislead": a one-file log shorter than 15 s holds out nothing, and
  // identify's and diagnose's held-out figures are all NaN; the note says why and what to do.
  const Eigen::VectorXd kt = Eigen::VectorXd::Ones(kSampleJoints);
  const SampleOptions options;
  const Log full = three_joint_log();  // 21 s: the block from 15 to 20 s is held out
  EXPECT_EQ(nothing_held_out_note(extract_joint_samples(full, kt, options), options), "");
  Log short_log = full;
  short_log.values = full.values.topRows(500).eval();  // 5 s
  const JointSamples s = extract_joint_samples(short_log, kt, options);
  const std::string note = nothing_held_out_note(s, options);
  EXPECT_NE(note.find("nothing is held out"), std::string::npos) << note;
  EXPECT_NE(note.find("spans 4.99 s"), std::string::npos) << note;
  EXPECT_NE(note.find("at least 20 s"), std::string::npos) << note;
  EXPECT_NE(note.find("several --log"), std::string::npos) << note;
  SampleOptions other_logs = options;  // the caller holds out other logs: nothing to say
  other_logs.hold_out = false;
  EXPECT_EQ(nothing_held_out_note(extract_joint_samples(short_log, kt, other_logs), other_logs),
            "");
}

// A log too short for a time step, or whose time stands still, is refused naming the log and the
// time column (it used to fail inside the acceleration filter: "cutoff … (nan Hz)").
TEST(JointSamples, ALogWithoutATimeStepIsRefusedNamingTheTimeColumn) {
  Log one_row = three_joint_log();
  one_row.source = "one.csv";
  one_row.values.conservativeResize(1, Eigen::NoChange);
  const Eigen::VectorXd kt = Eigen::VectorXd::Ones(kSampleJoints);
  try {
    extract_joint_samples(one_row, kt);
    ADD_FAILURE() << "a one-row log was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("one.csv: t: the log has 1 row(s)"), std::string::npos)
        << e.what();
  }
  Log frozen = three_joint_log();
  frozen.source = "frozen.csv";
  frozen.values.col(0).setConstant(3.0);
  try {
    extract_joint_samples(frozen, kt);
    ADD_FAILURE() << "a log whose time stands still was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("frozen.csv: t: the time column does not advance"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tpf::offline
