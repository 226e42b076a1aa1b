// `tpf import`'s core: a foreign CSV through a column map into a tpf log.
#include "offline/log/import_log.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "log_test_files.hpp"
#include "offline/log/gzip.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

using test::TempDir;
using test::write_text;

const char* kMap = R"({"format": "tpf-import", "version": 1, "joints": 2, "rate_hz": 100,
  "joint_order": [2, 1],
  "time": {"column": "Index", "unit": "sample"},
  "columns": {"q": {"source": "Pos{j}", "unit": "deg"}, "dq": {"source": "Vel{j}", "unit": "rad/s"},
              "i": {"source": "Cur{j}", "unit": "A"}, "tau_sensor": {"source": "Trq{j}", "unit": "N*m"}},
  "metadata": {"robot": "bench"}})";

const char* kCsv =
    "Index,Pos1,Pos2,Vel1,Vel2,Cur1,Cur2,Trq1,Trq2,Label\n"
    "10,90,0,1,2,0.5,1.5,3,4,start\n"
    "11,180,45,1,2,0.25,-1,3,4,x\n"
    "11,180,45,1,2,0.25,-1,3,4,repeat\n"
    "14,0,0,1,2,0,0,3,,late\n";

std::string error_of(const std::filesystem::path& csv, const ImportMap& map) {
  try {
    ImportReport report;
    import_log(csv, map, report);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

/// The message of the tpf::Error loading the map `map_file` throws (a failure if none).
std::string map_error_of(const std::filesystem::path& map_file) {
  try {
    load_import_map(map_file);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

TEST(ImportLog, MapsColumnsUnitsJointOrderAndTime) {
  TempDir dir("import");
  write_text(dir / "map.json", kMap);
  write_text(dir / "in.csv.gz", gzip(kCsv));
  const ImportMap map = load_import_map(dir / "map.json");
  ImportReport report;
  const Log log = import_log(dir / "in.csv.gz", map, report);
  EXPECT_EQ(log.columns, (std::vector<std::string>{"t", "q1", "q2", "dq1", "dq2", "i1", "i2",
                                                   "tau_sensor1", "tau_sensor2"}));
  ASSERT_EQ(log.rows(), 3);
  // sample index 10, 11, (11 dropped), 14 at 100 Hz
  EXPECT_DOUBLE_EQ(log.col("t")[0], 0.0);
  EXPECT_DOUBLE_EQ(log.col("t")[1], 0.01);
  EXPECT_DOUBLE_EQ(log.col("t")[2], 0.04);
  // tpf joint 1 is source joint 2; deg → rad, A → mA
  EXPECT_DOUBLE_EQ(log.col("q1")[1], std::numbers::pi / 4);
  EXPECT_DOUBLE_EQ(log.col("q2")[0], std::numbers::pi / 2);
  EXPECT_DOUBLE_EQ(log.col("i1")[0], 1500.0);
  EXPECT_DOUBLE_EQ(log.col("i2")[1], 250.0);
  EXPECT_DOUBLE_EQ(log.col("tau_sensor1")[0], 4.0);
  EXPECT_TRUE(std::isnan(log.col("tau_sensor1")[2]));
  EXPECT_EQ(log.meta.get("robot"), "bench");
  EXPECT_EQ(log.meta.get("rate_hz"), "100");
  // Every change to the time is counted.
  EXPECT_EQ(report.rows_read, 4u);
  EXPECT_EQ(report.rows_written, 3u);
  EXPECT_EQ(report.not_increasing, 1u);
  EXPECT_EQ(report.first_not_increasing_line, 4);
  EXPECT_EQ(report.irregular_steps, 1u);
  EXPECT_EQ(report.gap_steps, 1u);
  EXPECT_NEAR(report.largest_step_s, 0.03, 1e-12);
  EXPECT_EQ(report.largest_step_line, 5);
}

/// A 1-joint map of time in ms at `rate_hz`, rule 'regular'.
std::string regular_time_map(const std::string& rate_hz) {
  return R"({"format": "tpf-import", "version": 1, "joints": 1, "rate_hz": )" + rate_hz +
         R"(, "time": {"column": "time_ms", "unit": "ms", "rule": "regular"},
    "columns": {"q": {"source": "q{j}", "unit": "rad"}, "dq": {"source": "dq{j}", "unit": "rad/s"},
                "tau": {"source": "tau{j}", "unit": "Nm"}}})";
}

TEST(ImportLog, RegularRuleRewritesJitteredTime) {
  TempDir dir("import_regular");
  write_text(dir / "map.json", regular_time_map("10"));
  write_text(dir / "in.csv", "time_ms,q1,dq1,tau1\n0,0,0,1\n102,0,0,1\n260,0,0,1\n300,0,0,1\n");
  ImportReport report;
  const Log log = import_log(dir / "in.csv", load_import_map(dir / "map.json"), report);
  EXPECT_TRUE(report.made_regular);
  EXPECT_EQ(report.gap_steps, 1u);        // 158 ms > 1.5 × 100 ms
  EXPECT_EQ(report.irregular_steps, 2u);  // 158 and 40 ms; 102 is within 10 %
  EXPECT_NEAR(report.regular_max_shift_s, 0.06, 1e-12);
  EXPECT_NEAR(log.col("t")[3], 0.3, 1e-12);
  EXPECT_NEAR(log.col("t")[2], 0.2, 1e-12);
}

TEST(ImportLog, ARateTheTimeColumnContradictsIsRefused) {
  // 2.5 ms steps (400 Hz) recorded, 1000 Hz declared: 'regular' would have shrunk the time 2.5×.
  TempDir dir("import_rate");
  write_text(dir / "map.json", regular_time_map("1000"));
  write_text(dir / "in.csv", "time_ms,q1,dq1,tau1\n0,0,0,1\n2.5,0,0,1\n5,0,0,1\n7.5,0,0,1\n");
  const std::string message = error_of(dir / "in.csv", load_import_map(dir / "map.json"));
  EXPECT_NE(message.find("map.json: rate_hz: 1000 Hz is a step of 0.001 s, but the time column "
                         "of "),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("steps 0.0025 s at the median (400 Hz)"), std::string::npos) << message;
  // Within 10 % of the declared step (the jitter of a recording computer's clock) it imports.
  write_text(dir / "near.csv", "time_ms,q1,dq1,tau1\n0,0,0,1\n1.05,0,0,1\n2.1,0,0,1\n3,0,0,1\n");
  ImportReport report;
  const Log log = import_log(dir / "near.csv", load_import_map(dir / "map.json"), report);
  EXPECT_NEAR(log.col("t")[3], 0.003, 1e-15);
}

/// A 1-joint map (or of `joints` joints) whose column names hold no {j}.
std::string plain_names_map(int joints) {
  return R"({"format": "tpf-import", "version": 1, "joints": )" + std::to_string(joints) +
         R"(, "time": {"column": "time", "unit": "s"},
    "columns": {"q": {"source": "pos", "unit": "deg"}, "dq": {"source": "vel", "unit": "rad/s"},
                "tau": {"source": "torque{j}", "unit": "Nm"}}})";
}

TEST(ImportLog, AOneJointMapNamesItsColumnsWithoutJ) {
  // Was refused: "columns.q.source: 'pos' needs {j} where the joint number goes".
  TempDir dir("import_one_joint");
  write_text(dir / "map.json", plain_names_map(1));
  write_text(dir / "in.csv", "time,pos,vel,torque1\n0,90,0.5,1\n0.01,180,0.25,2\n");
  ImportReport report;
  const Log log = import_log(dir / "in.csv", load_import_map(dir / "map.json"), report);
  EXPECT_EQ(log.columns, (std::vector<std::string>{"t", "q1", "dq1", "tau1"}));
  ASSERT_EQ(log.rows(), 2);
  EXPECT_DOUBLE_EQ(log.col("q1")[1], std::numbers::pi);
  EXPECT_EQ(log.col("dq1")[0], 0.5);
  EXPECT_EQ(log.col("tau1")[1], 2.0);
}

TEST(ImportLog, AMapOfSeveralJointsNeedsJInEveryColumnName) {
  TempDir dir("import_two_joints");
  write_text(dir / "map2.json", plain_names_map(2));
  try {
    load_import_map(dir / "map2.json");
    FAIL() << "a 2-joint map with 'pos' for q was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              (dir / "map2.json").string() +
                  ": columns.q.source: 'pos' needs {j} where the joint number goes (the map has 2 "
                  "joints; only a 1-joint map may name its column without {j}; or give an array "
                  "of one name per joint)");
  }
}

TEST(ImportLog, ACutLastRowIsSkippedAndReported) {
  // "0.015,0.4,0,1.25" without its newline may be the start of "1.257": it was imported as 1.25.
  TempDir dir("import_cut_row");
  write_text(dir / "map.json", R"({"format": "tpf-import", "version": 1, "joints": 1,
    "time": {"column": "time", "unit": "s"},
    "columns": {"q": {"source": "q{j}", "unit": "rad"}, "dq": {"source": "dq{j}", "unit": "rad/s"},
                "tau": {"source": "tau{j}", "unit": "Nm"}}})");
  write_text(dir / "cut.csv",
             "time,q1,dq1,tau1\n0,0.1,0,1\n0.005,0.2,0,1\n0.010,0.3,0,1\n0.015,0.4,0,1.25");
  ImportReport report;
  const Log log = import_log(dir / "cut.csv", load_import_map(dir / "map.json"), report);
  ASSERT_EQ(log.rows(), 3);
  EXPECT_EQ(log.col("tau1")[2], 1.0);
  EXPECT_EQ(report.rows_read, 3u);
  const std::string note = (dir / "cut.csv").string() +
                           ":5: the file ends without a newline, inside this row: a cut file? "
                           "The row is skipped, its last field may be cut short";
  EXPECT_EQ(report.reader_notes, std::vector<std::string>{note});
  ASSERT_FALSE(report.lines().empty());
  EXPECT_EQ(report.lines().front(), note);
}

TEST(ImportLog, ErrorsNameFileLineAndColumn) {
  TempDir dir("import_errors");
  write_text(dir / "map.json", kMap);
  const ImportMap map = load_import_map(dir / "map.json");
  write_text(dir / "text.csv", std::string(kCsv) + "15,0,0,1,2,0,abc,3,4,x\n");
  std::string message = error_of(dir / "text.csv", map);
  EXPECT_NE(message.find("text.csv:6: Cur2: 'abc' is not a number"), std::string::npos) << message;
  write_text(dir / "missing.csv", "Index,Pos1,Pos2,Vel1,Vel2,Cur1,Cur2,Trq1\n1,1,1,1,1,1,1,1\n");
  message = error_of(dir / "missing.csv", map);
  EXPECT_NE(message.find("missing.csv:1: Trq2: the column named by"), std::string::npos) << message;
  write_text(dir / "notime.csv",
             "Index,Pos1,Pos2,Vel1,Vel2,Cur1,Cur2,Trq1,Trq2\n,1,1,1,1,1,1,1,1\n");
  message = error_of(dir / "notime.csv", map);
  EXPECT_NE(message.find("notime.csv:2: Index: the time is missing"), std::string::npos) << message;
  // A header without data rows wrote an empty log ("nominal step nan s").
  write_text(dir / "header_only.csv", "Index,Pos1,Pos2,Vel1,Vel2,Cur1,Cur2,Trq1,Trq2\n");
  message = error_of(dir / "header_only.csv", map);
  EXPECT_NE(message.find("header_only.csv:1: 0 data rows, 0 with an increasing time"),
            std::string::npos)
      << message;
  // A bad map names the map and the key.
  write_text(dir / "bad_unit.json", R"({"format": "tpf-import", "version": 1, "joints": 1,
    "time": {"column": "t"}, "columns": {"q": {"source": "q{j}", "unit": "grad"},
    "dq": {"source": "dq{j}", "unit": "rad/s"}, "i": {"source": "i{j}", "unit": "A"}}})");
  message = map_error_of(dir / "bad_unit.json");
  EXPECT_NE(message.find("bad_unit.json"), std::string::npos) << message;
  EXPECT_NE(message.find("'grad' is not one of rad, deg"), std::string::npos) << message;
  // Two efforts: the log would carry tau beside i, and every tool would read i alone.
  write_text(dir / "two_efforts.json", R"({"format": "tpf-import", "version": 1, "joints": 1,
    "time": {"column": "t"}, "columns": {"q": {"source": "q{j}", "unit": "rad"},
    "dq": {"source": "dq{j}", "unit": "rad/s"}, "i": {"source": "i{j}", "unit": "A"},
    "tau": {"source": "tau{j}", "unit": "N*m"}}})");
  message = map_error_of(dir / "two_efforts.json");
  EXPECT_NE(message.find("two_efforts.json"), std::string::npos) << message;
  EXPECT_NE(message.find("columns: maps both i and tau"), std::string::npos) << message;
}

}  // namespace
}  // namespace tpf::offline
