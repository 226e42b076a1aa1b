// The twin's true joint friction for any joint count: the LuGre parameters of each joint on its
// own (LuGreParameters<double, 1>), so the plant and the teaching controller evaluate tpf::core's
// per-joint friction functions without knowing N at compile time.
#pragma once

#include <string>
#include <vector>

#include "tpf/friction/lugre.hpp"

namespace tpf::offline {

using JointFriction = LuGreParameters<double, 1>;  ///< one joint's parameters (index 0)

struct TwinFriction {
  std::vector<JointFriction> joints;  ///< in chain order
  int count() const { return static_cast<int>(joints.size()); }
  const JointFriction& operator[](int j) const { return joints[static_cast<std::size_t>(j)]; }
  JointFriction& operator[](int j) { return joints[static_cast<std::size_t>(j)]; }
};

/// Reads a friction file (tpf/friction/friction_file.hpp, effort unit N·m, LuGre keys required)
/// for a robot of `joints` joints. Throws tpf::Error naming the file and field, e.g. when an array
/// has not one value per joint.
TwinFriction load_twin_friction(const std::string& path, int joints);

}  // namespace tpf::offline
