// tpf::Error: the one line a user reads, and the parts (file, line, field, message) a program
// reads, e.g. the Python module's tpf.Error.
#include "tpf/common/error.hpp"

#include <gtest/gtest.h>

namespace {

TEST(Error, AtJoinsItsPartsAndKeepsThem) {
  const tpf::Error e = tpf::Error::at("data/arm4.urdf", 12, "joint 'joint3'", "axis must be unit");
  EXPECT_STREQ(e.what(), "data/arm4.urdf:12: joint 'joint3': axis must be unit");
  EXPECT_EQ(e.file(), "data/arm4.urdf");
  EXPECT_EQ(e.line(), 12);
  EXPECT_EQ(e.field(), "joint 'joint3'");
  EXPECT_EQ(e.message(), "axis must be unit");
}

TEST(Error, AMessageWithColonsIsNotSplitByGuess) {
  // No line, no field: the message itself holds ": " and is kept whole.
  const tpf::Error e = tpf::Error::at("log.csv", 0, "", "column 'q1': not a number: abc");
  EXPECT_STREQ(e.what(), "log.csv: column 'q1': not a number: abc");
  EXPECT_EQ(e.line(), 0);
  EXPECT_EQ(e.field(), "");
  EXPECT_EQ(e.message(), "column 'q1': not a number: abc");
  // An error without a place: everything is the message.
  const tpf::Error plain("the model 'arm4' has 4 joints, the program asks for 7");
  EXPECT_EQ(plain.file(), "");
  EXPECT_EQ(plain.message(), plain.what());
}

TEST(Error, LineBreaksInQuotedTextBecomeSpaces) {
  const tpf::Error e = tpf::Error::at("robot.urdf", 3, "link 'a\nb'", "bad");
  EXPECT_STREQ(e.what(), "robot.urdf:3: link 'a b': bad");
  EXPECT_EQ(e.field(), "link 'a b'");
}

}  // namespace
