// Fuzz target: any bytes as a pad layout file → load_pads against the arm's link names.
// Contract: pads on moving links with unit normals and positive finite areas, or a one-line
// tpf::Error naming the file.
#include <cmath>

#include "fuzz_support.hpp"
#include "tpf/skin/pad_layout.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::vector<std::string> links = {"link1", "link2", "link3", "link4", "link5"};
  const auto path = tpf::fuzz::write_input({data, size}, "input.pads.json");
  tpf::fuzz::expect_clean_error(path.string(), [&] {
    for (const tpf::Pad& pad : tpf::load_pads(path, links)) {
      if (pad.link < 1 || pad.link >= static_cast<int>(links.size()))
        tpf::fuzz::violation("load_pads", "pad '" + pad.name + "' is not on a moving link");
      if (!(std::abs(pad.normal.norm() - 1.0) < 1e-9) || !pad.center.allFinite())
        tpf::fuzz::violation("load_pads", "pad '" + pad.name + "' has a bad normal or centre");
      if (!(pad.area > 0) || !std::isfinite(pad.area))
        tpf::fuzz::violation("load_pads", "pad '" + pad.name + "' has a bad area");
    }
  });
  return 0;
}
