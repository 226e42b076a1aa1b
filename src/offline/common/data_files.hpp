// Where the project's shipped data files are, for defaults in the command-line tools.
#pragma once

#include <filesystem>

namespace tpf::offline {

/// The data/ folder, first of: $TPF_DATA_DIR; the installed data beside the running program
/// (<prefix>/share/tpf for <prefix>/bin/tpf); the source tree's data/ folder (a build tree).
std::filesystem::path data_dir();

/// data_dir() / name.
std::filesystem::path data_file(const std::filesystem::path& name);

}  // namespace tpf::offline
