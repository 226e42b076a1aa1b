// Fuzz target: any bytes as an estimator parameter file (tpf-estimator) → load_estimator_parameters
// for 4 joints. Contract: a one-line tpf::Error naming the file, or parameters that are usable —
// σ's, dead bands and levels finite and in range — and that survive save → load unchanged (the
// second save writes the same bytes as the first).
#include <fstream>
#include <sstream>

#include "fuzz_support.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"

namespace {

std::string read_all(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tpf::fuzz::write_input({data, size}, "input.estimator.json");
  const std::string file = path.string();
  tpf::fuzz::expect_clean_error(file, [&] {
    const auto p = tpf::load_estimator_parameters<4>(file);
    const bool ok =
        p.sample_period_s > 0 && p.nominal_sigma.allFinite() && p.fused_sigma.allFinite() &&
        p.static_dead_band.allFinite() && (p.nominal_sigma.array() >= 0).all() &&
        (p.fused_sigma.array() >= 0).all() && (p.static_dead_band.array() >= 0).all() &&
        (p.compensator_speed_limit.array() > 0).all() &&
        (p.compensator_acceleration_limit.array() > 0).all() &&
        p.skin.detector.off_level_kpa < p.skin.detector.on_level_kpa && p.torque_alarm_samples >= 1;
    if (!ok) tpf::fuzz::violation("load_estimator_parameters", "a parameter is out of its range");
    const auto first = tpf::fuzz::scratch_dir() / "first.estimator.json";
    const auto second = tpf::fuzz::scratch_dir() / "second.estimator.json";
    tpf::save_estimator_parameters<4>(first, p, "fuzz");
    tpf::save_estimator_parameters<4>(second, tpf::load_estimator_parameters<4>(first), "fuzz");
    if (read_all(first) != read_all(second))
      tpf::fuzz::violation("save_estimator_parameters", "save → load → save changed the file");
  });
  return 0;
}
