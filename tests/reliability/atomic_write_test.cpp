// Files the core writes (TCN weights, parameter files) appear complete or not at all, also when
// the disk fills part-way: a child process writes under a 4 KiB file-size limit.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "core/common/atomic_file.hpp"
#include "tpf/common/error.hpp"
#include "tpf/nn/tcn_weight_file.hpp"

namespace tpf {
namespace {

/// A weight file of `hidden` channels (≈ 60·hidden² bytes of JSON).
TcnWeightFile weights(int hidden) {
  TcnWeightFile w;
  w.inputs = hidden, w.hidden = hidden, w.levels = 1, w.kernel = 2, w.outputs = 1;
  w.input_mean.assign(hidden, 0.125);
  w.input_std.assign(hidden, 1.5);
  const std::vector<double> values(static_cast<std::size_t>(hidden * hidden * 2), 0.1234567891);
  w.tensors[tcn_conv_weight_name(0)] = {{hidden, hidden, 2}, values};
  w.tensors[tcn_conv_bias_name(0)] = {{hidden}, std::vector<double>(hidden, 0.5)};
  for (bool high : {false, true}) {
    w.tensors[tcn_head_weight_name(high)] = {{1, hidden}, std::vector<double>(hidden, 0.25)};
    w.tensors[tcn_head_bias_name(high)] = {{1}, {0.0}};
  }
  return w;
}

/// Runs `write` in a child limited to 4 KiB per file (SIGXFSZ ignored, so writes fail with
/// EFBIG); returns the child's exit code: 0 written, 1 tpf::Error, 2 anything else.
template <typename Write>
int write_in_a_small_disk(Write&& write) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      write();
    } catch (const Error&) {
      ::_exit(1);
    } catch (...) {
      ::_exit(2);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// write_tcn_weight_file wrote straight to the target and checked the stream before its last
// flush: a full disk left a truncated weight file and no error. Now it is a temporary that is
// flushed, checked and renamed, or removed.
TEST(AtomicWrite, TcnWeightFileOnAFullDiskFailsAndLeavesTheOldFile) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("tpf_atomic_write_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "w.json").string();
  write_tcn_weight_file(path, weights(2));  // small: fits
  const TcnWeightFile before = read_tcn_weight_file(path);
  EXPECT_EQ(write_in_a_small_disk([&] { write_tcn_weight_file(path, weights(24)); }), 1);
  EXPECT_EQ(read_tcn_weight_file(path).hidden, before.hidden);  // the old file, whole
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator()),
            1)
      << "a temporary was left behind";
  std::filesystem::remove_all(dir);
}

/// Files in `dir`, hidden ones included.
int files_in(const std::filesystem::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir))
    ++n;
  return n;
}

/// A child that opens an AtomicFile in `dir`, writes half of it and is then killed by SIGTERM;
/// returns the signal that ended it.
int killed_mid_write(const std::filesystem::path& dir, bool cleanup_installed) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (cleanup_installed) remove_temporaries_on_termination();
    AtomicFile file(dir / "params.json");
    file.write("{\"format\": ");
    ::kill(::getpid(), SIGTERM);
    ::_exit(0);  // not reached: SIGTERM ends the child
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFSIGNALED(status) ? WTERMSIG(status) : 0;
}

// A `tpf` command killed while writing (Ctrl-C, a job scheduler's SIGTERM) left its hidden
// temporary behind; main() now installs remove_temporaries_on_termination().
TEST(AtomicWrite, AKilledWriterLeavesNoTemporaryOnceCleanupIsInstalled) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("tpf_killed_writer_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // Without the handlers the half-written temporary stays: the check below can fail.
  EXPECT_EQ(killed_mid_write(dir, false), SIGTERM);
  EXPECT_EQ(files_in(dir), 1);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  // With them, the process still ends by the same signal, and nothing is left.
  EXPECT_EQ(killed_mid_write(dir, true), SIGTERM);
  EXPECT_EQ(files_in(dir), 0);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tpf
