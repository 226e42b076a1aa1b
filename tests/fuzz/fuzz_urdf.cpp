// Fuzz target: any bytes as a URDF → load_urdf_chain → make_model<double, 4>. Contract: a chain
// of unit axes and finite, physically valid inertias, or a one-line tpf::Error naming the file.
#include <cmath>

#include "fuzz_support.hpp"
#include "tpf/model/load_robot.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tpf::fuzz::write_input({data, size}, "input.urdf");
  tpf::fuzz::expect_clean_error(path.string(), [&] {
    const tpf::ChainDescription chain = tpf::load_urdf_chain(path);
    if (chain.inertias.size() != chain.joints.size() + 1)
      tpf::fuzz::violation("load_urdf_chain", "one inertia per link expected");
    for (const tpf::ChainJoint& j : chain.joints) {
      if (!(std::abs(j.axis.norm() - 1.0) < 1e-9))
        tpf::fuzz::violation("load_urdf_chain", "axis of '" + j.name + "' is not a unit vector");
      if (!j.placement.R.allFinite() || !j.placement.p.allFinite())
        tpf::fuzz::violation("load_urdf_chain", "placement of '" + j.name + "' is not finite");
    }
    for (const auto& inertia : chain.inertias)
      if (!(inertia.mass >= 0.0) || !std::isfinite(inertia.mass))
        tpf::fuzz::violation("load_urdf_chain", "negative or non-finite mass accepted");
    if (chain.joints.size() == 4) static_cast<void>(tpf::make_model<double, 4>(chain));
  });
  return 0;
}
