#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "log_test_files.hpp"
#include "offline/log/log_writer.hpp"
#include "offline/log/read_log.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

using test::read_text;
using test::TempDir;
using test::write_text;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A small seeded log with hardware-like values, awkward doubles, NaNs and an unknown column.
Log sample_log() {
  Log log;
  log.meta.set("robot", "arm4");
  log.meta.set("rate_hz", "400");
  log.meta.set("x_custom", "a: b");
  log.columns = {"t", "q1", "dq1", "i1", "p1", "gt_fric1", "future_column"};
  const int rows = 500;
  log.values.resize(rows, 7);
  std::mt19937_64 rng(42);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int r = 0; r < rows; ++r) {
    log.values(r, 0) = r * 0.0025;
    log.values(r, 1) = std::round(noise(rng) * 150000) * 6.259113e-6;  // encoder pulses → rad
    log.values(r, 2) = std::round(noise(rng) * 3000) * 1.0471976e-3;   // 0.01 rpm → rad/s
    log.values(r, 3) = std::round(noise(rng) * 300);                   // 1 mA steps
    log.values(r, 4) = noise(rng) * 1e-7;
    log.values(r, 5) = noise(rng) * 1e12;
    log.values(r, 6) = (r % 17 == 0) ? kNaN : std::nextafter(1.0 / 3.0, 1.0) * r;
  }
  log.values(3, 1) = std::numeric_limits<double>::denorm_min();
  log.values(4, 1) = -0.0;
  log.values(5, 1) = std::numeric_limits<double>::max();
  return log;
}

void expect_same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  ASSERT_EQ(a.rows(), b.rows());
  ASSERT_EQ(a.cols(), b.cols());
  for (Eigen::Index c = 0; c < a.cols(); ++c)
    for (Eigen::Index r = 0; r < a.rows(); ++r) {
      if (std::isnan(a(r, c))) {
        ASSERT_TRUE(std::isnan(b(r, c))) << r << "," << c;
        continue;
      }
      ASSERT_EQ(a(r, c), b(r, c)) << r << "," << c;
      ASSERT_EQ(std::signbit(a(r, c)), std::signbit(b(r, c))) << r << "," << c;
    }
}

TEST(WriteLog, RoundTripIsExact) {
  TempDir dir("roundtrip");
  const Log original = sample_log();
  write_log(dir / "a.csv", original);
  const Log back = read_log(dir / "a.csv");
  EXPECT_EQ(back.columns, original.columns);
  expect_same_bits(original.values, back.values);
  EXPECT_EQ(back.meta.entries.front(), (std::pair<std::string, std::string>{"tpf-log", "1"}));
  EXPECT_EQ(back.meta.get("x_custom"), "a: b");
  EXPECT_EQ(back.meta.get("robot"), "arm4");
  EXPECT_EQ(back.quality.missing_per_column[6], 30u);  // rows 0, 17, ..., 493
  // Writing what was read gives the same bytes.
  write_log(dir / "b.csv", back);
  EXPECT_EQ(read_text(dir / "a.csv"), read_text(dir / "b.csv"));
  EXPECT_NE(read_text(dir / "a.csv").find("\n0.0025,"), std::string::npos);
}

// A metadata line without a key whose text holds a colon ("# :rate_hz: 40" read as key "" and
// text "rate_hz: 40") is written so that it reads back keyless, not as a rate_hz entry (a fuzz
// find: the copy used to fail on its rate).
TEST(WriteLog, AKeylessMetadataLineWithAColonStaysKeyless) {
  TempDir dir("keyless");
  write_text(dir / "a.csv", "# tpf-log: 1\n# :rate_hz: 40-x\n# note without a key\nt,q1\n0,1\n");
  const Log original = read_log(dir / "a.csv");
  ASSERT_EQ(original.meta.entries.size(), 3u);
  EXPECT_EQ(original.meta.entries[1], (std::pair<std::string, std::string>{"", "rate_hz: 40-x"}));
  write_log(dir / "b.csv", original);
  const Log back = read_log(dir / "b.csv");
  EXPECT_EQ(back.meta.entries, original.meta.entries);
  EXPECT_FALSE(back.meta.get("rate_hz").has_value());
}

TEST(WriteLog, RoundTripOfALogLargeEnoughForTwoThreads) {
  TempDir dir("roundtrip_big");
  Log log;
  log.columns = {"t", "v"};
  log.values.resize(100000, 2);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (int r = 0; r < 100000; ++r) {
    log.values(r, 0) = r / 400.0;
    log.values(r, 1) = u(rng);
  }
  write_log(dir / "a.csv", log);
  expect_same_bits(log.values, read_log(dir / "a.csv").values);
}

TEST(LogWriter, StreamsRowsAndRenamesOnClose) {
  TempDir dir("stream");
  const Log original = sample_log();
  {
    LogWriter writer(dir / "s.csv", original.meta, original.columns);
    for (Eigen::Index r = 0; r < original.values.rows(); ++r) {
      const Eigen::RowVectorXd row = original.values.row(r);
      writer.write_row(std::span<const double>(row.data(), static_cast<std::size_t>(row.size())));
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "s.csv"));
    writer.close();
    EXPECT_EQ(writer.rows_written(), 500u);
  }
  expect_same_bits(original.values, read_log(dir / "s.csv").values);
  write_log(dir / "w.csv", original);
  EXPECT_EQ(read_text(dir / "s.csv"), read_text(dir / "w.csv"));
  // Only the final file is left: no temporaries.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            2);
}

TEST(LogWriter, UnclosedWriterLeavesNothingBehind) {
  TempDir dir("unclosed");
  write_text(dir / "keep.csv", "t\n0\n");
  {
    LogWriter writer(dir / "keep.csv", {}, {"t", "q1"});
    const double row[] = {0.0, 1.0};
    writer.write_row(row);
  }
  EXPECT_EQ(read_text(dir / "keep.csv"), "t\n0\n");
  { LogWriter writer(dir / "new.csv", {}, {"t"}); }
  EXPECT_FALSE(std::filesystem::exists(dir / "new.csv"));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(LogWriter, RejectsBadRowsAndNames) {
  TempDir dir("reject");
  LogWriter writer(dir / "a.csv", {}, {"t", "q1"});
  const double good[] = {0.0, 1.0};
  writer.write_row(good);
  const double short_row[] = {0.1};
  EXPECT_THROW(writer.write_row(short_row), Error);
  const double infinite[] = {0.2, std::numeric_limits<double>::infinity()};
  EXPECT_THROW(writer.write_row(infinite), Error);
  const double backwards[] = {0.0, 1.0};
  EXPECT_THROW(writer.write_row(backwards), Error);
  EXPECT_THROW(LogWriter(dir / "b.csv", {}, {"t", "a,b"}), Error);
  EXPECT_THROW(LogWriter(dir / "c.csv", {}, {"t", "t"}), Error);
  EXPECT_THROW(LogWriter(dir / "no_such_dir" / "d.csv", {}, {"t"}), Error);
}

TEST(LogWriter, WritesNanAsNanAndVersionFirst) {
  TempDir dir("nan");
  LogMetadata meta;
  meta.set("note", "first");
  meta.set("tpf-log", "1");
  LogWriter writer(dir / "a.csv", meta, {"t", "q1"});
  const double row[] = {0.5, kNaN};
  writer.write_row(row);
  writer.close();
  EXPECT_EQ(read_text(dir / "a.csv"), "# tpf-log: 1\n# note: first\nt,q1\n0.5,nan\n");
}

TEST(LogAccessors, ColumnsJointsPadsAndEffort) {
  Log log;
  log.source = "x.csv";
  log.columns = {"t", "q1", "q2", "dq1", "dq2", "tau1", "tau2", "p1", "p2", "p10", "pz", "i1"};
  log.values = Eigen::MatrixXd::Zero(3, 12);
  EXPECT_EQ(log.column("q2"), 2);
  EXPECT_EQ(log.column("q3"), -1);
  EXPECT_EQ(log.joint_count(), 2);
  EXPECT_EQ(log.pad_count(), 3);
  EXPECT_EQ(log.effort_prefix(), "tau");
  log.col("q2")[1] = 5.0;
  EXPECT_EQ(log.values(1, 2), 5.0);
  try {
    log.col("ddq1");
    FAIL();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "x.csv: column 'ddq1' is missing");
  }
  log.columns[4] = "other";
  try {
    log.joint_count();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("column 'dq2' is missing"), std::string::npos);
  }
  log.columns[4] = "dq2";
  log.columns[6] = "tau3";
  EXPECT_THROW(log.effort_prefix(), Error);
  log.add_column("ddq1", Eigen::VectorXd::Constant(3, 2.0));
  EXPECT_EQ(log.col("ddq1")[2], 2.0);
  EXPECT_THROW(log.add_column("ddq1"), Error);
}

TEST(LogMetadata, SetReplacesOrAppends) {
  LogMetadata meta;
  meta.set("a", "1");
  meta.set("b", "2");
  meta.set("a", "3");
  ASSERT_EQ(meta.entries.size(), 2u);
  EXPECT_EQ(meta.get("a"), "3");
  EXPECT_FALSE(meta.get("c"));
  EXPECT_TRUE(std::isnan(meta.rate_hz()));
  meta.set("rate_hz", "-4");
  EXPECT_THROW(meta.rate_hz(), Error);
}

}  // namespace
}  // namespace tpf::offline
