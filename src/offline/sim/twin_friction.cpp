#include "offline/sim/twin_friction.hpp"

#include "offline/sim/scenario.hpp"
#include "tpf/common/error.hpp"
#include "tpf/friction/friction_file.hpp"

namespace tpf::offline {

namespace {

template <int N>
TwinFriction split(const LuGreParameters<double, N>& p) {
  TwinFriction f;
  f.joints.resize(N);
  for (int j = 0; j < N; ++j) {
    JointFriction& o = f[j];
    o.stribeck.coulomb[0] = p.stribeck.coulomb[j];
    o.stribeck.static_friction[0] = p.stribeck.static_friction[j];
    o.stribeck.stribeck_velocity[0] = p.stribeck.stribeck_velocity[j];
    o.stribeck.stribeck_exponent[0] = p.stribeck.stribeck_exponent[j];
    o.stribeck.viscous[0] = p.stribeck.viscous[j];
    o.stribeck.load_coulomb[0] = p.stribeck.load_coulomb[j];
    o.stribeck.load_viscous[0] = p.stribeck.load_viscous[j];
    o.bristle_stiffness[0] = p.bristle_stiffness[j];
    o.bristle_damping[0] = p.bristle_damping[j];
  }
  return f;
}

template <int N>
TwinFriction load(const std::string& path, int joints) {
  if constexpr (N > kTwinMaxJoints) {
    throw Error::at(path, 0, "", "the twin simulates 1 to 7 joints, not " + std::to_string(joints));
  } else {
    if (joints == N) return split<N>(load_lugre_parameters<double, N>(path));
    return load<N + 1>(path, joints);
  }
}

}  // namespace

TwinFriction load_twin_friction(const std::string& path, int joints) {
  if (friction_effort_unit(path) != "N*m")
    throw Error::at(path, 0, "effort_unit", "the twin's true friction must be in N*m");
  return load<1>(path, joints);
}

}  // namespace tpf::offline
