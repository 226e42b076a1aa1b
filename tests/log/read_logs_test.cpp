// Several log files as one log: segments in time, file_starts, common columns; sensor report.
#include "offline/log/read_logs.hpp"

#include <gtest/gtest.h>

#include "log_test_files.hpp"
#include "offline/log/torque_sensor.hpp"
#include "offline/signal/segments.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

using test::TempDir;
using test::write_text;

/// rows samples at 100 Hz from t0, q = k, tau_sensor1 = sensor(k).
std::string log_text(double t0, int rows, const std::string& extra_column, double sensor_slope) {
  std::string text = "# rate_hz: 100\nt,q1,dq1,i1,tau_sensor1" + extra_column + "\n";
  for (int k = 0; k < rows; ++k)
    text += std::to_string(t0 + 0.01 * k) + "," + std::to_string(k) + ",1,2," +
            std::to_string(sensor_slope * k) + (extra_column.empty() ? "" : ",9") + "\n";
  return text;
}

TEST(ReadLogs, TheReadersNotesAreSaidOnce) {
  TempDir dir("reader_notes");
  std::string cut = log_text(0.0, 30, "", 0.1);
  cut.pop_back();  // no final newline: the last row is skipped
  write_text(dir / "a.csv", cut);
  write_text(dir / "b.csv", log_text(0.0, 20, "", 0.1));
  const std::string note = (dir / "a.csv").string() +
                           ":32: the file ends without a newline, inside this row: a cut file? "
                           "The row is skipped, its last field may be cut short";
  const std::vector<std::filesystem::path> both{dir / "a.csv", dir / "b.csv"};
  // Handed to the caller's notes (which identify, diagnose and validate print) ...
  std::vector<std::string> notes;
  Log log = read_logs(both, &notes);
  EXPECT_EQ(notes, std::vector<std::string>{note});
  EXPECT_TRUE(log.quality.notes.empty());
  EXPECT_EQ(log.rows(), 29 + 20);
  EXPECT_EQ(log.quality.skipped_rows, 1u);
  EXPECT_NE(log.quality.summary().find("2 files, 49 rows (1 more skipped), "), std::string::npos)
      << log.quality.summary();
  notes.clear();
  log = read_logs(std::vector<std::filesystem::path>{dir / "a.csv"}, &notes);
  EXPECT_EQ(notes, std::vector<std::string>{note});
  EXPECT_TRUE(log.quality.notes.empty());
  // ... else kept in the quality, whose summary says them.
  log = read_logs(both);
  EXPECT_EQ(log.quality.notes, std::vector<std::string>{note});
  EXPECT_NE(log.quality.summary().find("\n  " + note), std::string::npos) << log.quality.summary();
}

TEST(ReadLogs, ConcatenatesFilesAsSeparateSegments) {
  TempDir dir("several");
  write_text(dir / "a.csv", log_text(5.0, 30, "", 0.1));
  write_text(dir / "b.csv", log_text(0.0, 20, ",extra", 0.0));
  std::vector<std::string> notes;
  const Log log =
      read_logs(std::vector<std::filesystem::path>{dir / "a.csv", dir / "b.csv"}, &notes);
  EXPECT_EQ(log.file_starts, (std::vector<Eigen::Index>{0, 30}));
  ASSERT_EQ(log.rows(), 50);
  EXPECT_EQ(log.columns, (std::vector<std::string>{"t", "q1", "dq1", "i1", "tau_sensor1"}));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("b.csv: columns not in every file, left out: extra"), std::string::npos);
  // Own steps kept, file b starts one seam (1 s) after file a's last sample.
  const auto t = log.col("t");
  EXPECT_DOUBLE_EQ(t[0], 5.0);
  EXPECT_DOUBLE_EQ(t[30] - t[29], 1.0);
  EXPECT_NEAR(t[31] - t[30], 0.01, 1e-12);
  EXPECT_EQ(log.col("q1")[30], 0.0);
  // Every tool's segmentation splits at the seam.
  const auto segments = contiguous_segments(log.col("t"), log.col("q1"));
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[1].begin, 30);
  EXPECT_EQ(log.quality.gap_rows, (std::vector<std::size_t>{30}));
  EXPECT_EQ(log.quality.seams, 1u);
  EXPECT_EQ(log.file_rows(1), (std::pair<Eigen::Index, Eigen::Index>{30, 50}));
  EXPECT_EQ(log.file_path(1), (dir / "b.csv").string());
  EXPECT_NE(log.quality.summary().find("2 files, 50 rows"), std::string::npos)
      << log.quality.summary();
  EXPECT_NEAR(log.quality.duration_s, 0.29 + 0.19, 1e-9);

  // The sensor varies in a, is flat (0) in b.
  const auto sensors = torque_sensor_columns(log, 1);
  EXPECT_EQ(sensors[0][0].state, SensorState::Varies);
  EXPECT_EQ(sensors[1][0].state, SensorState::Flat);
  const auto report = torque_sensor_report(log, 1);
  ASSERT_EQ(report.size(), 1u);
  EXPECT_NE(report[0].find("b.csv: flat (range < 0.05 N*m) on joints 1 (j1 0 N*m)"),
            std::string::npos)
      << report[0];
}

TEST(ReadLogs, OneFileIsReadLogAndErrorsNameTheFile) {
  TempDir dir("single");
  write_text(dir / "a.csv", log_text(0.0, 10, "", 0.0));
  write_text(dir / "bad.csv", "t,q1\n0,1\n0.01,x\n");
  const Log one = read_logs(std::vector<std::filesystem::path>{dir / "a.csv"});
  EXPECT_EQ(one.file_starts, (std::vector<Eigen::Index>{0}));
  EXPECT_EQ(one.source, (dir / "a.csv").string());
  EXPECT_EQ(torque_sensor_report(one, 1).size(), 1u);  // flat
  try {
    read_logs(std::vector<std::filesystem::path>{dir / "a.csv", dir / "bad.csv"});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:3: q1: 'x' is not a number"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(read_logs(std::vector<std::filesystem::path>{}), Error);
}

TEST(TorqueSensor, MissingColumnsAreNamed) {
  TempDir dir("nosensor");
  write_text(dir / "a.csv", "t,q1,dq1,q2,dq2,tau_sensor2\n0,0,0,0,0,1\n0.1,0,0,0,0,3\n");
  const Log log = read_logs(std::vector<std::filesystem::path>{dir / "a.csv"});
  const auto report = torque_sensor_report(log, 2);
  ASSERT_EQ(report.size(), 1u);
  EXPECT_NE(report[0].find("missing on joints 1"), std::string::npos) << report[0];
  write_text(dir / "b.csv", "t,q1,dq1\n0,0,0\n0.1,0,0\n");
  EXPECT_EQ(torque_sensor_report(read_logs(std::vector<std::filesystem::path>{dir / "b.csv"}), 1),
            (std::vector<std::string>{"torque sensor: none (no tau_sensor<j> column)"}));
}

}  // namespace
}  // namespace tpf::offline
