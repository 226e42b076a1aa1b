// The smallest tpf controller: load the arm once, then compute the motor currents that hold it
// against gravity at each cycle. Usage: gravity_compensation <robot.json>
#include <cstdio>
#include <tpf/core.hpp>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s <robot file, e.g. data/arm4.robot.json>\n", argv[0]);
    return 2;
  }
  constexpr int N = 4;
  try {
    const auto model = tpf::load_robot<double, N>(argv[1]);  // start-up: may allocate and throw
    tpf::Data<double, N> data(model);
    tpf::JointVector<double, N> q = tpf::JointVector<double, N>::Zero();
    for (int cycle = 0; cycle < 5; ++cycle) {  // the per-cycle path: no allocation, no exception
      q(1) = 0.2 * cycle;
      const auto& g = tpf::compute_gravity(model, data, q);
      const tpf::JointVector<double, N> current_mA =
          1000.0 * g.cwiseQuotient(model.torque_constant);
      std::printf("q2 = %.1f rad: holding currents [mA] %8.1f %8.1f %8.1f %8.1f\n", q(1),
                  current_mA(0), current_mA(1), current_mA(2), current_mA(3));
    }
  } catch (const tpf::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
