#include "offline/common/data_files.hpp"

#include <cstdlib>
#include <system_error>

namespace tpf::offline {
namespace {

/// <prefix>/share/tpf when the running program is <prefix>/bin/<program> and that folder holds
/// the twin's robot file; empty otherwise (a build tree, or a program that is not installed).
std::filesystem::path installed_data_dir() {
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return {};
  const std::filesystem::path dir =
      (program.parent_path() / TPF_INSTALLED_DATA_FROM_BIN).lexically_normal();
  if (!std::filesystem::is_regular_file(dir / "arm4.robot.json", error)) return {};
  return dir;
}

}  // namespace

std::filesystem::path data_dir() {
  if (const char* env = std::getenv("TPF_DATA_DIR"); env != nullptr && *env != '\0') return env;
  static const std::filesystem::path installed = installed_data_dir();
  if (!installed.empty()) return installed;
  return TPF_DATA_DIR;
}

std::filesystem::path data_file(const std::filesystem::path& name) {
  return data_dir() / name;
}

}  // namespace tpf::offline
