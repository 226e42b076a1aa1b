// Fuzz target: any bytes as a friction parameter file → Stribeck and LuGre loaders for 4 joints.
// Contract: finite parameters, or a one-line tpf::Error naming the file.
#include "fuzz_support.hpp"
#include "tpf/friction/friction_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = tpf::fuzz::write_input({data, size}, "input.friction.json");
  const std::string file = path.string();
  tpf::fuzz::expect_clean_error(file, [&] {
    const auto p = tpf::load_stribeck_parameters<double, 4>(file);
    // The documented ranges: τ_c, τ_s, b, α ≥ 0 and q̇_s, δ > 0, all finite.
    const bool ok = p.coulomb.allFinite() && p.static_friction.allFinite() &&
                    p.viscous.allFinite() && p.stribeck_velocity.allFinite() &&
                    p.stribeck_exponent.allFinite() && p.load_coulomb.allFinite() &&
                    p.load_viscous.allFinite() && (p.coulomb.array() >= 0).all() &&
                    (p.static_friction.array() >= 0).all() && (p.viscous.array() >= 0).all() &&
                    (p.stribeck_velocity.array() > 0).all() &&
                    (p.stribeck_exponent.array() > 0).all();
    if (!ok) tpf::fuzz::violation("load_stribeck_parameters", "a parameter is out of its range");
  });
  tpf::fuzz::expect_clean_error(file, [&] {
    const auto p = tpf::load_lugre_parameters<double, 4>(file);
    if (!p.bristle_stiffness.allFinite() || !p.bristle_damping.allFinite() ||
        !(p.bristle_stiffness.array() > 0).all() || !(p.bristle_damping.array() >= 0).all())
      tpf::fuzz::violation("load_lugre_parameters", "a parameter is not finite");
  });
  tpf::fuzz::expect_clean_error(file, [&] {
    const std::string unit = tpf::friction_effort_unit(file);
    if (unit != "N*m" && unit != "mA") tpf::fuzz::violation("friction_effort_unit", unit);
  });
  return 0;
}
