// The check every file-writing subcommand makes before any work: no output is the same file as
// one of its inputs (the write would destroy it) or as another output (the second write would
// replace the first), and none is a directory.
#pragma once

#include <string>
#include <vector>

namespace tpf::cli {

/// A path given to (or derived from) an option, e.g. {"--log", "ex.csv"}.
struct PathOption {
  std::string option;
  std::string path;  ///< empty: the option was not given, skipped
};

using PathOptions = std::vector<PathOption>;

/// One PathOption per path given to the repeatable `option`.
PathOptions each_of(const std::string& option, const std::vector<std::string>& paths);

/// `first`, then `second`.
PathOptions joined(PathOptions first, const PathOptions& second);

/// Throws tpf::Error "tpf <command>: --out p.json is the same file as --log p.json: it would
/// overwrite the input; choose another output path" when an output and an input are the same
/// file (std::filesystem::equivalent, or equal weakly canonical paths for a file that does not
/// exist yet), and the like when two outputs are, or when an output is an existing directory
/// (the write would fail only after the work).
void refuse_overwriting_inputs(const std::string& command, const PathOptions& inputs,
                               const PathOptions& outputs);

/// The files a compensator weights path given to `option` stands for: the path itself and the
/// <stem>.joint<j>.json files beside it that exist, joint1 onwards up to the first missing.
PathOptions weight_files(const std::string& option, const std::string& path);

/// The files a compensator of `joints` joints is written to from `path` (train's --out,
/// --checkpoint): the path itself, or per joint <stem>.joint<j>.json.
PathOptions written_weight_files(const std::string& option, const std::string& path, bool per_joint,
                                 int joints);

}  // namespace tpf::cli
