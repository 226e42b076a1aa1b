// Where the project's shipped data files are, for defaults in the command-line tools.
#pragma once

#include <filesystem>

namespace tpf::offline {

/// The data/ folder: $TPF_DATA_DIR if set, else the source tree's data/ folder.
std::filesystem::path data_dir();

/// data_dir() / name.
std::filesystem::path data_file(const std::filesystem::path& name);

}  // namespace tpf::offline
