// Motion onsets per file and joint of a folder of logs: how many starts from rest and reversals
// each recording offers to score the static-to-kinetic regime on.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "offline/regimes/motion_events.hpp"

namespace tpf::offline {

struct FileOnsets {
  std::string file;                  ///< file name
  std::vector<MotionEvents> joints;  ///< per joint, over the whole file
  /// The joint that moves (|q̇| ≥ reversal_velocity somewhere) when it is the only one, else −1.
  int single_joint = -1;
};

/// count_motion_events over every row of each *.csv.gz / *.csv log in `folder` (sorted by name).
/// Throws tpf::Error naming a file that cannot be read.
std::vector<FileOnsets> count_file_onsets(const std::filesystem::path& folder,
                                          double reversal_velocity);

}  // namespace tpf::offline
