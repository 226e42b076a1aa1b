// The loop's recorder writes tpf's log format through the project's one writer: the tools' reader
// gets back every value, NaN for what was missing, and the estimator's columns.
#include "arm/log_recorder.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "offline/log/read_log.hpp"
#include "tpf/common/error.hpp"

namespace tpf::arm {
namespace {

std::string temp_log(const std::string& name) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir ? dir : "/tmp") + "/tpf_recorder_" + std::to_string(::getpid()) + "_" +
         name;
}

offline::LogMetadata test_metadata() {
  offline::LogMetadata meta;
  meta.set("robot", "arm2");
  meta.set("rate_hz", "400");
  meta.set("note", "simulated: unit test");
  return meta;
}

CycleSample two_joint_sample(double t) {
  CycleSample s;
  s.t = t;
  s.joints = 2;
  s.pads = 1;
  s.motors_valid = true;
  s.q = {0.5, -1.25};
  s.dq = {0.125, 0.0};
  s.i = {100.0, -200.0};
  s.p[0] = 1.5f;
  return s;
}

TEST(LogRecorder, TheToolsReadBackEveryValueAndNanForWhatWasMissing) {
  const std::string path = temp_log("plain.csv");
  {
    LogRecorder log(path, RecordedColumns{2, 1, false}, test_metadata(), 16);
    CycleSample s = two_joint_sample(0.0025);
    s.pads_valid = false;
    EXPECT_TRUE(log.push(s));
    s.t = 0.005;
    s.motors_valid = false;  // failed read: no invented values
    s.pads_valid = true;
    EXPECT_TRUE(log.push(s));
  }  // the destructor drains and puts the log in place
  const offline::Log log = offline::read_log(path);
  EXPECT_EQ(log.meta.get("robot"), "arm2");
  EXPECT_EQ(log.meta.rate_hz(), 400.0);
  EXPECT_EQ(log.columns, recorded_column_names({2, 1, false}));
  EXPECT_EQ(log.joint_count(), 2);
  EXPECT_EQ(log.pad_count(), 1);
  ASSERT_EQ(log.rows(), 2);
  EXPECT_EQ(log.col("t")[0], 0.0025);  // shortest round-trip numbers: exact
  EXPECT_EQ(log.col("q2")[0], -1.25);
  EXPECT_EQ(log.col("dq1")[0], 0.125);
  EXPECT_EQ(log.col("i2")[0], -200.0);
  EXPECT_TRUE(std::isnan(log.col("p1")[0]));
  EXPECT_TRUE(std::isnan(log.col("q1")[1]));
  EXPECT_TRUE(std::isnan(log.col("i2")[1]));
  EXPECT_EQ(log.col("p1")[1], 1.5);
  std::filesystem::remove(path);
}

TEST(LogRecorder, TheEstimatorsAnswerHasItsColumns) {
  const std::string path = temp_log("estimates.csv.gz");  // compressed as it goes
  {
    LogRecorder log(path, RecordedColumns{2, 1, true}, test_metadata(), 16);
    CycleSample s = two_joint_sample(0.0025);
    s.pads_valid = true;
    s.estimate.present = true;
    s.estimate.status = 0;
    s.estimate.contact = true;
    s.estimate.contact_pad = 0;
    s.estimate.external_torque_nm = {0.75, -2.5};
    s.estimate.force_world_n = {1.0, -3.0, 4.5};
    EXPECT_TRUE(log.push(s));
    s.t = 0.005;
    s.estimate.present = false;  // a skipped cycle: no estimate, its reason in the status
    s.estimate.status = 1u;
    EXPECT_TRUE(log.push(s));
    log.close();
    EXPECT_EQ(log.rows_written(), 2u);
    EXPECT_EQ(log.rows_failed(), 0u);
  }
  const offline::Log log = offline::read_log(path);
  EXPECT_EQ(log.columns.back(), "est_status");
  ASSERT_EQ(log.rows(), 2);
  EXPECT_EQ(log.col("est_tau_ext1")[0], 0.75);
  EXPECT_EQ(log.col("est_tau_ext2")[0], -2.5);
  EXPECT_EQ(log.col("est_contact")[0], 1.0);
  EXPECT_EQ(log.col("est_pad")[0], 1.0);  // 1-based as gt_contact, 0: none
  EXPECT_EQ(log.col("est_fz")[0], 4.5);
  EXPECT_EQ(log.col("est_status")[0], 0.0);
  EXPECT_TRUE(std::isnan(log.col("est_tau_ext1")[1]));
  EXPECT_TRUE(std::isnan(log.col("est_fx")[1]));
  EXPECT_EQ(log.col("est_status")[1], 1.0);
  std::filesystem::remove(path);
}

TEST(LogRecorder, AnUnwritableFolderIsAnErrorNamingThePath) {
  try {
    LogRecorder log("/nonexistent-folder/x.csv", RecordedColumns{1, 0, false}, test_metadata());
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/x.csv"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tpf::arm
