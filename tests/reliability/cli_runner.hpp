// Runs the `tpf` binary (path from CMake) in a scratch folder, bounded in time, and captures its
// exit code and output, for tests of the command line under bad input.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/temp_dir.hpp"

namespace tpf::test {

/// The shipped data folder (data/): robot, parameter and scenario files the CLI tests start from.
inline const std::string kShippedData = TPF_TEST_DATA_DIR;

/// What one run of a command printed and returned.
struct CliResult {
  int exit_code = -1;  ///< the process's exit status; 128 + n when signal n ended it
  std::string out;
  std::string err;
};

/// A fresh folder under $TMPDIR, removed at the end; runs `tpf` inside it.
class CliSandbox {
 public:
  explicit CliSandbox(const std::string& name) : folder_("reliability_" + name) {}

  std::filesystem::path operator/(const std::string& file) const { return folder_ / file; }
  const std::filesystem::path& dir() const { return folder_.path(); }

  /// Writes `text` to `<dir>/<file>` and returns the path.
  std::filesystem::path write(const std::string& file, const std::string& text) const {
    std::ofstream(folder_ / file, std::ios::binary) << text;
    return folder_ / file;
  }

  /// Runs `<shell_prefix> tpf <args>` in the folder, killed after `limit_s` seconds.
  /// `shell_prefix` may set limits first, e.g. "ulimit -f 64;".
  CliResult tpf(const std::string& args, const std::string& shell_prefix = "",
                int limit_s = 120) const {
    return sh(shell_prefix + " timeout -k 5 " + std::to_string(limit_s) + " \"$TPF\" " + args);
  }

  /// Runs a /bin/sh script in the folder with $TPF set to the tpf binary; captures its output.
  /// Under LeakSanitizer, urdfdom's own leak on a URDF it cannot build a tree from is suppressed
  /// (tests/fuzz/urdfdom.lsan.supp), so that the messages of a sanitized tpf are compared.
  CliResult sh(const std::string& script) const {
    const std::string command =
        "cd '" + dir().string() +
        "' && TPF='" TPF_CLI "' && export LSAN_OPTIONS=suppressions='" TPF_URDFDOM_LSAN_SUPPRESSIONS
        ":print_suppressions=0' && { " +
        script + "; } >.stdout 2>.stderr";
    const int status = std::system(command.c_str());
    CliResult r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = slurp(folder_ / ".stdout");
    r.err = slurp(folder_ / ".stderr");
    std::filesystem::remove(folder_ / ".stdout");
    std::filesystem::remove(folder_ / ".stderr");
    return r;
  }

  /// Names of the files in the folder (hidden temporaries included), sorted.
  std::vector<std::string> files() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(dir()))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  static std::string slurp(const std::filesystem::path& path) {
    std::ostringstream s;
    s << std::ifstream(path, std::ios::binary).rdbuf();
    return s.str();
  }

 private:
  TempDir folder_;
};

/// Number of lines of `text` (a final line without '\n' counts).
inline int line_count(const std::string& text) {
  int n = 0;
  for (char c : text)
    n += c == '\n';
  return n + (!text.empty() && text.back() != '\n');
}

}  // namespace tpf::test
