// The loop's CSV writer: tpf log v1 metadata and header, nan for missing values, row order.
#include "arm/csv_log_writer.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace tpf::arm {
namespace {

TEST(CsvLogWriter, WritesHeaderRowsAndNanForMissingValues) {
  const char* dir = std::getenv("TMPDIR");
  const std::string path =
      std::string(dir ? dir : "/tmp") + "/tpf_csv_writer_" + std::to_string(::getpid()) + ".csv";
  {
    CsvLogWriter log(path, 2, 1, LogMetadata{"arm2", 400.0, "simulated: unit test"}, 16);
    CycleSample s;
    s.joints = 2;
    s.pads = 1;
    s.motors_valid = true;
    s.pads_valid = false;
    s.t = 0.0025;
    s.q = {0.5, -1.25};
    s.dq = {0.125, 0.0};
    s.i = {100.0, -200.0};
    s.p[0] = 1.5f;
    EXPECT_TRUE(log.push(s));
    s.t = 0.005;
    s.motors_valid = false;  // failed read: no invented values
    s.pads_valid = true;
    EXPECT_TRUE(log.push(s));
  }  // the destructor drains and closes
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[0], "# tpf-log: 1");
  EXPECT_EQ(lines[1], "# robot: arm2");
  EXPECT_EQ(lines[2], "# rate_hz: 400");
  EXPECT_EQ(lines[3], "# note: simulated: unit test");
  EXPECT_EQ(lines[4], "t,q1,q2,dq1,dq2,i1,i2,p1");
  EXPECT_EQ(lines[5], "0.002500,0.5,-1.25,0.125,0,100,-200,nan");
  EXPECT_EQ(lines[6], "0.005000,nan,nan,nan,nan,nan,nan,1.5");
  ::unlink(path.c_str());
}

}  // namespace
}  // namespace tpf::arm
