// The progress bar of long offline jobs: redrawn in place on a terminal, a line per update into a
// file or a pipe (where "\r" would pile thousands of redraws onto one line).
#include "offline/compensator_training/progress_bar.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

namespace tpf::offline {
namespace {

TEST(ProgressBar, RedrawsInPlaceOnATerminal) {
  std::ostringstream out;
  TerminalProgressBar bar(out, 10, /*redraw=*/true);
  bar.update(0.5, "epoch 5/10", 65.0);
  bar.update(1.0, "epoch 10/10", 0.0);
  EXPECT_EQ(out.str().find('\n'), std::string::npos);
  bar.finish();
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\r'), 2);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1);
  EXPECT_NE(text.find("\r[#####.....]  50%  epoch 5/10  ETA 1m05s"), std::string::npos);
  EXPECT_NE(text.find("\r[##########] 100%  epoch 10/10  ETA 0s"), std::string::npos);
}

TEST(ProgressBar, WritesALinePerUpdateElsewhere) {
  std::ostringstream out;
  TerminalProgressBar bar(out, 10, /*redraw=*/false);
  bar.update(0.25, "net 1", -1.0);
  bar.update(2.0, "net 1", 3725.0);  // clamped to 100 %
  bar.finish();
  EXPECT_EQ(out.str(), "[###.......]  25%  net 1\n[##########] 100%  net 1  ETA 1h02m\n");
}

}  // namespace
}  // namespace tpf::offline
