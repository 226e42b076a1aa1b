// Fuzz target: any bytes as a TCN weight file → read_tcn_weight_file → load into a small compiled
// network (2 inputs, 4 channels, 2 levels, kernel 2, 1 output). Contract: finite folded weights
// (the normalisation 1/σ included), or a one-line tpf::Error naming the file.
#include <memory>

#include "fuzz_support.hpp"
#include "tpf/nn/load_tcn_weights.hpp"

namespace {
using SmallTcn = tpf::Tcn<double, 2, 4, 2, 2, 1>;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tpf::fuzz::write_input({data, size}, "input.weights.json");
  const std::string file = path.string();
  tpf::fuzz::expect_clean_error(file, [&] {
    auto tcn = std::make_unique<SmallTcn>();
    tpf::load_tcn_weights(file, *tcn);
    const auto& w = tcn->weights();
    bool finite = w.input_projection.allFinite() && w.input_bias.allFinite() &&
                  w.low_weight.allFinite() && w.high_weight.allFinite();
    for (const auto& tap : w.input_taps)
      finite = finite && tap.allFinite();
    if (!finite) tpf::fuzz::violation("load_tcn_weights", "folded weights are not finite");
  });
  return 0;
}
