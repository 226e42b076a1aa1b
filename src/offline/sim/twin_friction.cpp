#include "offline/sim/twin_friction.hpp"

#include "tpf/common/error.hpp"
#include "tpf/friction/friction_file.hpp"

namespace tpf::offline {

namespace {

// One LuGreParameters<double, 1> per joint of a friction file's parameters.
TwinFriction one_per_joint(const LuGreParameters<double, Eigen::Dynamic>& p) {
  const int n = static_cast<int>(p.bristle_stiffness.size());
  TwinFriction f;
  f.joints.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
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

}  // namespace

TwinFriction load_twin_friction(const std::string& path, int joints) {
  if (friction_effort_unit(path) != "N*m")
    throw Error::at(path, 0, "effort_unit", "the twin's true friction must be in N*m");
  return one_per_joint(load_lugre_parameters(path, joints));
}

}  // namespace tpf::offline
