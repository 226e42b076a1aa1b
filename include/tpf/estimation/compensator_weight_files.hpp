// Which weight files a compensator path stands for, as found on disk (start-up code).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tpf {

/// How a compensator's weights are laid out in files.
enum class CompensatorLayout { None, AllJoints, PerJoint };

/// The weight files of one compensator.
struct CompensatorWeightFiles {
  CompensatorLayout layout = CompensatorLayout::None;
  int hidden = 0;                  ///< channels of the network(s)
  std::vector<std::string> files;  ///< one (AllJoints) or one per joint in joint order (PerJoint)
  std::string source;              ///< the path they were found from, for messages
};

/// Per-joint weight file of joint j (0-based) for `path`: "<dir>/<stem>.joint<j+1>.json".
std::filesystem::path joint_weight_path(const std::filesystem::path& path, int joint);

/// The weights of a `joints`-joint compensator at `path`: `path` itself when it exists (one
/// network for all joints: inputs 5N, outputs N), else `<stem>.joint1.json` …
/// `.joint<joints>.json` (one network per joint: 5 inputs, 1 output, all of one hidden size).
/// An empty path: no compensator. Throws tpf::Error naming the path when neither exists or a file
/// has the wrong shape.
CompensatorWeightFiles find_compensator_weights(const std::filesystem::path& path, int joints);

/// The held-out gate (start-up): bit j set when joint j's network may be used, that is when its
/// weight file holds no held-out score or its gain is ≥ min_gain in every regime scored (per
/// joint: that joint's file; all joints: output j of the one file). `gated`, when given, gets one
/// line per joint gated off ("joint 2: held-out gain −9.5 % at moving < 0 %"). No compensator:
/// every bit (nothing to gate). Throws tpf::Error naming a file that cannot be read.
std::uint32_t compensated_joints(const CompensatorWeightFiles& weights, int joints, double min_gain,
                                 std::vector<std::string>* gated = nullptr);

/// "per-joint networks of 16 channels", "one network of 32 channels", "no compensator".
std::string describe(const CompensatorWeightFiles& weights);

}  // namespace tpf
