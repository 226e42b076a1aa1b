#include "output_collisions.hpp"

#include <filesystem>
#include <system_error>

#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"
#include "tpf/estimation/compensator_weight_files.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace tpf::cli {
namespace {

/// A path option with its absolute, weakly canonical form (symbolic links resolved as far as the
/// path exists), so that a file not written yet compares too.
struct Resolved {
  const PathOption* given;
  std::filesystem::path canonical;
};

std::filesystem::path comparable(const std::string& path) {
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(path, error);
  if (error) return std::filesystem::path(path).lexically_normal();
  const std::filesystem::path full = std::filesystem::weakly_canonical(absolute, error);
  return error ? absolute.lexically_normal() : full;
}

std::vector<Resolved> resolve(const PathOptions& options) {
  std::vector<Resolved> resolved;
  for (const PathOption& o : options)
    if (!o.path.empty()) resolved.push_back({&o, comparable(o.path)});
  return resolved;
}

/// Equal canonical paths, or one file under two names (a hard link).
bool same_file(const Resolved& a, const Resolved& b) {
  if (a.canonical == b.canonical) return true;
  std::error_code error;
  return std::filesystem::equivalent(a.given->path, b.given->path, error) && !error;
}

[[noreturn]] void refuse(const std::string& command, const PathOption& output,
                         const PathOption& other, const std::string& why) {
  throw Error("tpf " + command + ": " + output.option + " " + output.path +
              " is the same file as " + other.option + " " + other.path + ": " + why);
}

}  // namespace

PathOptions each_of(const std::string& option, const std::vector<std::string>& paths) {
  PathOptions all;
  for (const std::string& path : paths)
    all.push_back({option, path});
  return all;
}

PathOptions joined(PathOptions first, const PathOptions& second) {
  first.insert(first.end(), second.begin(), second.end());
  return first;
}

void refuse_overwriting_inputs(const std::string& command, const PathOptions& inputs,
                               const PathOptions& outputs) {
  const std::vector<Resolved> in = resolve(inputs);
  const std::vector<Resolved> out = resolve(outputs);
  for (const Resolved& o : out) {  // found only at the write, after all the work
    std::error_code error;
    if (std::filesystem::is_directory(o.canonical, error))
      throw Error("tpf " + command + ": " + o.given->option + " " + o.given->path +
                  " is a directory: give the path of a file to write");
  }
  for (std::size_t o = 0; o < out.size(); ++o) {
    for (const Resolved& i : in)
      if (same_file(out[o], i))
        refuse(command, *out[o].given, *i.given,
               "it would overwrite the input; choose another output path");
    for (std::size_t earlier = 0; earlier < o; ++earlier)
      if (same_file(out[o], out[earlier]))
        refuse(command, *out[o].given, *out[earlier].given,
               "the second write would replace the first; give each output its own path");
  }
}

PathOptions weight_files(const std::string& option, const std::string& path) {
  if (path.empty()) return {};
  PathOptions files{{option, path}};
  // Per-joint files are joint1, joint2, … up to the arm's joint count: up to the first missing.
  for (int j = 0;; ++j) {
    const std::filesystem::path joint = joint_weight_path(path, j);
    std::error_code error;
    if (!std::filesystem::exists(joint, error)) break;
    files.push_back({option, joint.string()});
  }
  return files;
}

PathOptions written_weight_files(const std::string& option, const std::string& path, bool per_joint,
                                 int joints) {
  if (path.empty()) return {};
  if (!per_joint) return {{option, path}};
  PathOptions files;
  for (int j = 0; j < joints; ++j)
    files.push_back({option, joint_weight_path(path, j).string()});
  return files;
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
