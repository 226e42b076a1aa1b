#include "offline/common/data_files.hpp"

#include <cstdlib>

namespace tpf::offline {

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("TPF_DATA_DIR"); env != nullptr && *env != '\0') return env;
  return TPF_DATA_DIR;
}

std::filesystem::path data_file(const std::filesystem::path& name) {
  return data_dir() / name;
}

}  // namespace tpf::offline
