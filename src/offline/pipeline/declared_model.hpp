// The declared nominal model of the arm, straight from its files (no identification).
#pragma once

#include <filesystem>

#include "offline/common/run_time_types.hpp"

namespace tpf::offline {

/// The model the robot files declare: rigid body and armature of the robot file (as base
/// parameters) and the memoryless Stribeck + load friction of the friction file (which must be in
/// N·m; tpf::Error naming the file otherwise), for an arm of any joint count. It is the starting
/// point of identification, and what the pipeline uses when no identified tpf-params file is
/// given.
NominalModelX declared_nominal_model(const std::filesystem::path& robot_file,
                                     const std::filesystem::path& friction_file);

}  // namespace tpf::offline
