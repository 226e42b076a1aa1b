// The declared nominal model of the arm, straight from its files (no identification).
#pragma once

#include <filesystem>
#include <string>

#include "offline/replay/replay_estimator.hpp"

namespace tpf::offline {

/// The model the robot files declare: rigid body and armature of the robot file (as base
/// parameters) and the memoryless Stribeck + load friction of the friction file (which must be in
/// N·m; tpf::Error naming the file otherwise). It is the starting point of identification, and
/// what the pipeline uses when no identified tpf-params file is given. Compiled for N = 1 …
/// kMaxJoints.
template <int N>
NominalModel<double, N> declared_nominal_model(const std::filesystem::path& robot_file,
                                               const std::filesystem::path& friction_file);

}  // namespace tpf::offline
