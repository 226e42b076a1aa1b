#include "offline/log/read_log.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "log_test_files.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

using test::TempDir;
using test::write_text;

/// The message of the tpf::Error that read_log throws for `text`.
std::string read_error(const TempDir& dir, const std::string& text) {
  const auto path = dir / "bad.csv";
  write_text(path, text);
  try {
    read_log(path);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}

TEST(ReadLog, MetadataColumnsAndValues) {
  TempDir dir("basic");
  write_text(dir / "a.csv",
             "# tpf-log: 1\n# robot: arm4\n# rate_hz: 400\n# custom_key: kept: with colon\n"
             "# free comment\n"
             "q1,t,dq1,i1,p1,my_extra\n"
             "0.5,0.0,1e-3,-12,3.25,7\n"
             "0.25,0.0025,-2.5E-1,+4,,nan\n");
  const Log log = read_log(dir / "a.csv");
  EXPECT_EQ(log.source, (dir / "a.csv").string());
  ASSERT_EQ(log.meta.entries.size(), 5u);
  EXPECT_EQ(log.meta.get("robot"), "arm4");
  EXPECT_EQ(log.meta.get("custom_key"), "kept: with colon");
  EXPECT_EQ(log.meta.entries[4].first, "");
  EXPECT_EQ(log.meta.entries[4].second, "free comment");
  EXPECT_EQ(log.meta.version(), 1);
  EXPECT_DOUBLE_EQ(log.meta.rate_hz(), 400.0);
  ASSERT_EQ(log.columns, (std::vector<std::string>{"q1", "t", "dq1", "i1", "p1", "my_extra"}));
  ASSERT_EQ(log.values.rows(), 2);
  EXPECT_EQ(log.col("t")[1], 0.0025);
  EXPECT_EQ(log.col("dq1")[0], 1e-3);
  EXPECT_EQ(log.col("dq1")[1], -0.25);
  EXPECT_EQ(log.col("i1")[1], 4.0);
  EXPECT_EQ(log.col("my_extra")[0], 7.0);
  EXPECT_TRUE(std::isnan(log.col("p1")[1]));
  EXPECT_TRUE(std::isnan(log.col("my_extra")[1]));
  EXPECT_EQ(log.quality.rows, 2u);
  EXPECT_EQ(log.quality.missing_per_column, (std::vector<std::size_t>{0, 0, 0, 0, 1, 1}));
  EXPECT_EQ(log.quality.missing_total(), 2u);
  EXPECT_EQ(log.quality.gaps, 0u);
  EXPECT_EQ(log.joint_count(), 1);
  EXPECT_EQ(log.pad_count(), 1);
  EXPECT_EQ(log.effort_prefix(), "i");
  EXPECT_NE(log.quality.summary(log.columns).find("p1: 1"), std::string::npos);
}

TEST(ReadLog, CrLfSpacesAndNoVersionLine) {
  TempDir dir("crlf");
  write_text(dir / "a.csv", "t, q1 ,dq1\r\n0, 1.5 ,2\r\n0.1,NaN,  3\r\n");
  const Log log = read_log(dir / "a.csv");
  EXPECT_EQ(log.meta.version(), 1);
  EXPECT_EQ(log.columns[1], "q1");
  EXPECT_EQ(log.col("q1")[0], 1.5);
  EXPECT_TRUE(std::isnan(log.col("q1")[1]));
  EXPECT_EQ(log.col("dq1")[1], 3.0);
}

TEST(ReadLog, ByteOrderMarkAndSummary) {
  TempDir dir("bom");
  write_text(dir / "a.csv",
             "\xEF\xBB\xBF# tpf-log: 1\n# rate_hz: 400\nt,q1\n0,1\n0.0025,\n0.01,2\n");
  const Log log = read_log(dir / "a.csv");
  EXPECT_EQ(log.meta.entries.front().first, "tpf-log");
  EXPECT_EQ(log.quality.summary(log.columns),
            "3 rows, 0.0 s at 400 Hz; 1 gap; 1 missing value\n  missing per column: q1: 1");
  EXPECT_EQ(log.quality.summary(),
            "3 rows, 0.0 s at 400 Hz; 1 gap; 1 missing value\n  missing per column: column 2: 1");
}

TEST(ReadLog, GapsAreCountedFromRateOrMedianStep) {
  TempDir dir("gaps");
  // 400 Hz: dt = 2.5 ms; 3.75 ms is the gap limit. Rows 3 and 6 follow gaps.
  const std::string body = "t,q1\n0,0\n0.0025,0\n0.005,0\n0.010,0\n0.0125,0\n0.0150,0\n0.0200,0\n";
  write_text(dir / "a.csv", "# rate_hz: 400\n" + body);
  const Log with_rate = read_log(dir / "a.csv");
  EXPECT_EQ(with_rate.quality.gaps, 2u);
  EXPECT_EQ(with_rate.quality.gap_rows, (std::vector<std::size_t>{3, 6}));
  write_text(dir / "b.csv", body);
  const Log without_rate = read_log(dir / "b.csv");
  EXPECT_DOUBLE_EQ(without_rate.quality.rate_hz, 400.0);
  EXPECT_EQ(without_rate.quality.gap_rows, (std::vector<std::size_t>{3, 6}));
  EXPECT_NEAR(without_rate.quality.duration_s, 0.02, 1e-15);
  // Jitter below 1.5 periods is not a gap.
  write_text(dir / "c.csv", "# rate_hz: 400\nt\n0\n0.0037\n0.0050\n");
  EXPECT_EQ(read_log(dir / "c.csv").quality.gaps, 0u);
}

TEST(ReadLog, EmptyFileAndHeaderOnly) {
  TempDir dir("empty");
  EXPECT_NE(read_error(dir, "").find("empty"), std::string::npos);
  EXPECT_NE(read_error(dir, "# tpf-log: 1\n").find("no header"), std::string::npos);
  write_text(dir / "h.csv", "# tpf-log: 1\nt,q1,dq1\n");
  const Log log = read_log(dir / "h.csv");
  EXPECT_EQ(log.values.rows(), 0);
  EXPECT_EQ(log.values.cols(), 3);
  EXPECT_EQ(log.quality.rows, 0u);
  EXPECT_EQ(log.quality.missing_per_column, (std::vector<std::size_t>{0, 0, 0}));
}

TEST(ReadLog, RefusesNewerMajorVersion) {
  TempDir dir("version");
  const std::string message = read_error(dir, "# robot: x\n# tpf-log: 2\nt\n0\n");
  EXPECT_NE(message.find("bad.csv:2: tpf-log: version 2 is newer"), std::string::npos) << message;
  write_text(dir / "minor.csv", "# tpf-log: 1.3\nt\n0\n");
  EXPECT_NO_THROW(read_log(dir / "minor.csv"));
  EXPECT_NE(read_error(dir, "# tpf-log: one\nt\n0\n").find("bad.csv:1: tpf-log"),
            std::string::npos);
}

TEST(ReadLog, MalformedLinesNameFileLineAndColumn) {
  TempDir dir("malformed");
  const std::string head = "# tpf-log: 1\nt,q1,dq1\n0,1,2\n";
  std::string message = read_error(dir, head + "0.1,abc,2\n");
  EXPECT_NE(message.find("bad.csv:4: q1: 'abc' is not a number"), std::string::npos) << message;
  message = read_error(dir, head + "0.1,1.5x,2\n");
  EXPECT_NE(message.find("bad.csv:4: q1: '1.5x' is not a number"), std::string::npos) << message;
  message = read_error(dir, head + "0.1,1\n");
  EXPECT_NE(message.find("bad.csv:4: expected 3 fields, found 2"), std::string::npos) << message;
  message = read_error(dir, head + "0.1,1,2,3\n");
  EXPECT_NE(message.find("bad.csv:4: expected 3 fields, found 4"), std::string::npos) << message;
  message = read_error(dir, head + "0.1,1,inf\n");
  EXPECT_NE(message.find("bad.csv:4: dq1: 'inf' is not a finite number"), std::string::npos)
      << message;
  message = read_error(dir, head + "0.1,1,1e999\n");
  EXPECT_NE(message.find("bad.csv:4: dq1: '1e999' is out of range"), std::string::npos) << message;
  message = read_error(dir, "t,q1,q1\n");
  EXPECT_NE(message.find("bad.csv:1: q1: column name appears twice"), std::string::npos) << message;
  message = read_error(dir, "q1,dq1\n1,2\n");
  EXPECT_NE(message.find("bad.csv:1: t: the required time column is missing"), std::string::npos)
      << message;
}

TEST(ReadLog, ALastRowWithoutItsNewlineIsSkippedAndSaid) {
  // A recorder stopped mid-write: "0.1,1,3" may be the start of "0.1,1,3.25". It was read as 3.
  TempDir dir("cut_row");
  const std::string note =
      ":3: the file ends without a newline, inside this row: a cut file? The row is skipped, its "
      "last field may be cut short";
  for (const std::string cut : {"0.1,1,3", "0.1,1", "0.1,1,", "0.1,1,3\r", "0.1,1,3 "}) {
    write_text(dir / "cut.csv", "t,q1,dq1\n0,1,2\n" + cut);
    const Log log = read_log(dir / "cut.csv");
    ASSERT_EQ(log.rows(), 1) << cut;
    EXPECT_EQ(log.col("dq1")[0], 2.0);
    EXPECT_EQ(log.quality.rows, 1u);
    EXPECT_EQ(log.quality.skipped_rows, 1u);
    EXPECT_EQ(log.quality.notes, std::vector<std::string>{(dir / "cut.csv").string() + note});
    EXPECT_EQ(log.quality.summary(log.columns),
              "1 rows (1 more skipped), 0.0 s at 0 Hz; 0 gaps; no missing values\n  " +
                  (dir / "cut.csv").string() + note);
  }
  // The only data row cut: a log without rows, said.
  write_text(dir / "one.csv", "# tpf-log: 1\nt,q1\n\n0,1.2");
  const Log one = read_log(dir / "one.csv");
  EXPECT_EQ(one.rows(), 0);
  EXPECT_EQ(one.quality.notes,
            std::vector<std::string>{(dir / "one.csv").string() +
                                     ":4: the file ends without a newline, inside this row: a "
                                     "cut file? The row is skipped, its last field may be cut "
                                     "short"});
  // More fields than the header is no cut: the line's error as before.
  const std::string message = read_error(dir, "t,q1,dq1\n0,1,2\n0.1,1,2,3");
  EXPECT_NE(message.find("bad.csv:3: expected 3 fields, found 4"), std::string::npos) << message;
  // A file that ends with its newline (or blank lines after it) keeps every row.
  write_text(dir / "ok.csv", "t,q1,dq1\n0,1,2\n0.1,1,3\n \n");
  const Log ok = read_log(dir / "ok.csv");
  EXPECT_EQ(ok.col("dq1")[1], 3.0);
  EXPECT_EQ(ok.quality.skipped_rows, 0u);
  EXPECT_TRUE(ok.quality.notes.empty());
}

TEST(ReadLog, ARateHzTheTimeColumnContradictsIsFlaggedAndTheTimeColumnUsed) {
  TempDir dir("rate");
  // rate_hz says 400 Hz; the time column steps 5 ms (200 Hz): every step was a gap at 400 Hz.
  std::string rows = "t,q1\n";
  for (int k = 0; k <= 10; ++k)
    rows += std::to_string(0.005 * k) + ",0\n";
  write_text(dir / "a.csv", "# tpf-log: 1\n# rate_hz: 400\n" + rows);
  const Log log = read_log(dir / "a.csv");
  EXPECT_NEAR(log.quality.rate_hz, 200.0, 1e-9);
  EXPECT_EQ(log.quality.gaps, 0u);
  EXPECT_EQ(log.quality.notes,
            std::vector<std::string>{(dir / "a.csv").string() +
                                     ":2: rate_hz: the metadata says 400 Hz, but the time "
                                     "column's median step is 0.005 s (200 Hz); the time column "
                                     "is used: gaps are found at 200 Hz"});
  EXPECT_EQ(log.meta.get("rate_hz"), "400");  // the metadata itself is kept as written
  // Within 1 % the metadata's rate stands: steps of 2.52 ms (0.8 % off 400 Hz).
  rows = "t,q1\n";
  for (int k = 0; k <= 10; ++k)
    rows += std::to_string(0.00252 * k) + ",0\n";
  write_text(dir / "b.csv", "# rate_hz: 400\n" + rows);
  const Log close = read_log(dir / "b.csv");
  EXPECT_EQ(close.quality.rate_hz, 400.0);
  EXPECT_TRUE(close.quality.notes.empty());
}

TEST(ReadLog, TimeMustBePresentAndIncrease) {
  TempDir dir("time");
  std::string message = read_error(dir, "t,q1\n0,1\n0.1,1\n0.1,1\n");
  EXPECT_NE(message.find("bad.csv:4: t: t = 0.10000000000000001 does not increase"),
            std::string::npos)
      << message;
  message = read_error(dir, "t,q1\n0,1\n-1,1\n");
  EXPECT_NE(message.find("bad.csv:3: t: t = -1 does not increase"), std::string::npos) << message;
  message = read_error(dir, "t,q1\n0,1\n,1\n");
  EXPECT_NE(message.find("bad.csv:3: t: the sample time is missing"), std::string::npos) << message;
}

TEST(ReadLog, MissingFileIsAClearError) {
  TempDir dir("nofile");
  try {
    read_log(dir / "absent.csv");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("absent.csv: cannot open"), std::string::npos);
  }
}

TEST(ReadLog, ErrorsInTheSecondParallelChunkNameTheRightLine) {
  TempDir dir("parallel");
  std::string text = "# tpf-log: 1\nt,a,b,c,d\n";
  constexpr int kRows = 60000;  // > 256 KiB of data: parsed on two threads
  for (int r = 0; r < kRows; ++r) {
    text += std::to_string(r) + ".5,1.25,-2.5,";
    text += (r == 50000) ? "x" : "3";
    text += ",123456.789\n";
  }
  const std::string message = read_error(dir, text);
  EXPECT_NE(message.find("bad.csv:50003: c: 'x' is not a number"), std::string::npos) << message;
}

TEST(ReadLog, ParallelParseMatchesEveryValue) {
  TempDir dir("parallel_ok");
  std::string text = "t,a,b\n";
  constexpr int kRows = 70000;
  for (int r = 0; r < kRows; ++r)
    text += std::to_string(r) + "," + std::to_string(r % 7) + "," +
            (r % 1000 == 999 ? "" : std::to_string(-r)) + "\n";
  write_text(dir / "big.csv", text);
  const Log log = read_log(dir / "big.csv");
  ASSERT_EQ(log.values.rows(), kRows);
  for (int r = 0; r < kRows; ++r) {
    ASSERT_EQ(log.values(r, 0), r);
    ASSERT_EQ(log.values(r, 1), r % 7);
    if (r % 1000 != 999) {
      ASSERT_EQ(log.values(r, 2), -r);
    }
  }
  EXPECT_EQ(log.quality.missing_per_column[2], 70u);
}

/// A log of `rows` lines with CR LF line ends, spaces around fields, missing values and a last
/// line without its line end, then blank lines: every awkward break the reader accepts.
std::string awkward_log(int rows, int bad_row = -1) {
  std::string text = "# tpf-log: 1\r\n# rate_hz: 400\r\nt, a ,b,c\r\n";
  for (int r = 0; r < rows; ++r) {
    char line[160];
    std::snprintf(line, sizeof line, "%.17g, %.17g ,%s,%s", 0.0025 * r, std::sin(0.37 * r),
                  r % 97 == 5 ? "" : "-1.5e-3", r == bad_row ? "x42" : "+42");
    text += line;
    if (r + 1 < rows) text += (r % 3 == 0) ? "\n" : "\r\n";
  }
  return text + "\r\n \r\n\n";
}

/// Line `line` (1-based) of `text` and what follows it.
std::string from_line(const std::string& text, int line) {
  std::size_t pos = 0;
  for (int l = 1; l < line; ++l)
    pos = text.find('\n', pos) + 1;
  return text.substr(pos);
}

TEST(ReadLog, TwoHalfParseEqualsOnePassParseOfEachHalf) {
  TempDir dir("halves");
  constexpr int kRows = 12000;  // ≈ 600 KB: parsed on two threads; each half alone on one
  const std::string text = awkward_log(kRows);
  write_text(dir / "whole.csv", text);
  const Log whole = read_log(dir / "whole.csv");
  ASSERT_EQ(whole.values.rows(), kRows);
  // The same lines as two files, each below the parallel threshold (parsed in one pass).
  constexpr int kFirst = 5003;
  const std::string header = "# rate_hz: 400\nt, a ,b,c\n";
  std::string first_text = text.substr(0, text.size() - from_line(text, 4 + kFirst).size());
  write_text(dir / "first.csv", first_text);
  write_text(dir / "second.csv", header + from_line(text, 4 + kFirst));
  const Log first = read_log(dir / "first.csv"), second = read_log(dir / "second.csv");
  ASSERT_EQ(first.values.rows() + second.values.rows(), kRows);
  for (Eigen::Index r = 0; r < kRows; ++r)
    for (Eigen::Index c = 0; c < 4; ++c) {
      const double expected = r < kFirst ? first.values(r, c) : second.values(r - kFirst, c);
      const double got = whole.values(r, c);
      ASSERT_TRUE(got == expected || (std::isnan(got) && std::isnan(expected)))
          << "row " << r << " column " << c;
    }
  for (std::size_t c = 0; c < 4; ++c)
    EXPECT_EQ(whole.quality.missing_per_column[c],
              first.quality.missing_per_column[c] + second.quality.missing_per_column[c]);
  EXPECT_EQ(whole.quality.missing_per_column[2], 124u);
}

TEST(ReadLog, ErrorsAroundTheSplitNameTheirLine) {
  TempDir dir("split_errors");
  constexpr int kRows = 12000;
  // The data is split just after the first line end past its middle byte: find that row.
  const std::string good = awkward_log(kRows);
  const std::size_t data_begin = good.find("t, a ,b,c\r\n") + 11;
  std::size_t data_end = good.size();
  while (std::string_view("\r\n \t").find(good[data_end - 1]) != std::string_view::npos)
    --data_end;
  const std::size_t split = good.find('\n', data_begin + (data_end - data_begin) / 2) + 1;
  const int split_row = static_cast<int>(std::count(good.begin() + static_cast<long>(data_begin),
                                                    good.begin() + static_cast<long>(split), '\n'));
  for (int row : {0, split_row - 1, split_row, split_row + 1, kRows - 1}) {
    // The bad field is as long as the good one: the split stays at the same row.
    const std::string message = read_error(dir, awkward_log(kRows, row));
    const std::string where = "bad.csv:" + std::to_string(4 + row) + ": c: 'x42' is not a number";
    EXPECT_NE(message.find(where), std::string::npos) << "row " << row << ": " << message;
  }
}

TEST(ReadLog, ColumnFilterSkipsTheOthersUnparsed) {
  TempDir dir("filter");
  write_text(dir / "a.csv", "# rate_hz: 400\nt,q1,note,gt_x\n0,1,text,1e308\n0.0025,2,more,,\n");
  // A skipped column may hold text; the field count is still checked.
  EXPECT_THROW(read_log(dir / "a.csv", [](std::string_view n) { return n != "note"; }), Error);
  write_text(dir / "b.csv", "# rate_hz: 400\nt,q1,note,gt_x\n0,1,text,5\n0.0025,2,more,\n");
  const Log log = read_log(dir / "b.csv", [](std::string_view n) { return n == "t" || n == "q1"; });
  EXPECT_EQ(log.columns, (std::vector<std::string>{"t", "q1"}));
  EXPECT_EQ(log.col("q1")[1], 2.0);
  EXPECT_EQ(log.quality.missing_per_column, (std::vector<std::size_t>{0, 0}));
}

TEST(ReadLog, SkippedLastColumnsGiveTheSameFieldCountErrors) {
  // The columns after the last kept one are only counted, not walked field by field: a wrong
  // count is reported as when every column is parsed.
  TempDir dir("skipped_tail");
  const std::string head = "# rate_hz: 400\nt,q1,gt_a,gt_b\n0,1,2,3\n";
  const auto message = [&](const std::string& text, const ColumnFilter& filter) {
    write_text(dir / "a.csv", text);
    try {
      read_log(dir / "a.csv", filter);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const ColumnFilter fitted = [](std::string_view name) { return name == "t" || name == "q1"; };
  for (const std::string tail : {"0.0025,2,3\n0.005,1,2,3\n", "0.0025,2,3,4,5\n", "0.0025,2\n",
                                 "0.0025,2,3,4\n0.005,1,2,3,\n", "0.0025,2,3,4\n0.005,2,3,4,5"}) {
    const std::string all = message(head + tail, {});
    EXPECT_NE(all, "no error") << tail;
    EXPECT_EQ(message(head + tail, fitted), all) << tail;
  }
  EXPECT_EQ(message(head + "0.0025,2,x,y\n", fitted), "no error");
  // A last row the file ends inside is skipped whichever columns are kept.
  for (const std::string tail : {"0.0025,2,3,4\n0.005,2,3", "0.0025,2,3,4\n0.005,2,3,"}) {
    EXPECT_EQ(message(head + tail, {}), "no error") << tail;
    EXPECT_EQ(message(head + tail, fitted), "no error") << tail;
    EXPECT_EQ(read_log(dir / "a.csv", fitted).quality.skipped_rows, 1u) << tail;
  }
}

TEST(ReadLog, OneLineLongerThanHalfTheDataIsParsedWhole) {
  TempDir dir("long_line");
  // Above the parallel threshold, with no line end after the middle of the data.
  write_text(dir / "a.csv", "t,text\n0,a\n1," + std::string(300000, 'b') + "\n");
  const CsvTable table =
      read_csv_table(dir / "a.csv", [](std::string_view name) { return name == "t"; });
  ASSERT_EQ(table.log.values.rows(), 2);
  EXPECT_EQ(table.log.values(1, 0), 1.0);
}

}  // namespace
}  // namespace tpf::offline
