// Fuzz target: any bytes as a twin scenario file → load_scenario. Contract: a scenario with
// positive finite durations and rates, or a one-line tpf::Error naming the file.
#include <cmath>

#include "fuzz_support.hpp"
#include "offline/sim/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tpf::fuzz::write_input({data, size}, "input.scenario.json");
  const std::string file = path.string();
  tpf::fuzz::expect_clean_error(file, [&] {
    const tpf::offline::Scenario s = tpf::offline::load_scenario(file);
    if (!(s.duration_s > 0) || !std::isfinite(s.duration_s) || !(s.log_rate_hz > 0) ||
        !(s.inner_rate_hz >= s.log_rate_hz) || !std::isfinite(s.inner_rate_hz) ||
        !s.initial_q.allFinite())
      tpf::fuzz::violation("load_scenario", "durations, rates or the initial pose are unusable");
  });
  return 0;
}
