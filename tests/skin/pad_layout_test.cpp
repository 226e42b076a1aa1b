// Pad layout files: duplicate pad names are refused, naming the file and the name.
#include "tpf/skin/pad_layout.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "support/arm_fixture.hpp"
#include "support/temp_dir.hpp"
#include "tpf/common/error.hpp"

namespace {

/// This file's layouts, removed at the program's end.
const tpf::test::TempDir kLayoutFiles("pad_layout_test");

/// A layout of pads named `names`, each on the arm's link3.
std::string layout_path(const std::string& file, const std::vector<std::string>& names) {
  std::string pads;
  for (const std::string& name : names)
    pads += std::string(pads.empty() ? "" : ", ") + R"({"name": ")" + name +
            R"(", "link": "link3", "center": [0, 0, 0.1], "normal": [1, 0, 0], "area": 0.0006})";
  const auto path = kLayoutFiles / file;
  std::ofstream(path) << R"({"format": "tpf-pads", "version": 1, "pads": [)" << pads << "]}";
  return path.string();
}

std::string layout_error(const std::string& path) {
  try {
    tpf::load_pads(path, tpf::test::arm());
  } catch (const tpf::Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PadLayout, DuplicatePadNameIsRefusedNamingFileAndName) {
  // Was: both loaded; the name no longer told the pads apart (tpf info, the pad messages).
  const std::string path = layout_path("twice.pads.json", {"elbow", "wrist", "elbow"});
  EXPECT_EQ(layout_error(path), path +
                                    ": pads[2].name: 'elbow' is also the name of pads[0]; each "
                                    "pad needs its own name");
  const std::string distinct = layout_path("distinct.pads.json", {"elbow", "wrist", "Elbow"});
  EXPECT_EQ(tpf::load_pads(distinct, tpf::test::arm()).size(), 3u);
}

}  // namespace
