// Files that appear complete or not at all: written to a hidden temporary beside the target and
// renamed into place on commit(); removed when dropped uncommitted, and — once
// remove_temporaries_on_termination() is installed — when the process is interrupted or killed.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string_view>

namespace tpf {

/// Writes `<dir>/.<name>.tmp.<pid>.<n>` and renames it to `path` on commit() (rename(2) is atomic
/// within a file system; no fsync). Readers never see a half-written file. Throws tpf::Error
/// naming the path on any I/O failure.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path path);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  /// Not committed → the temporary is closed and removed; the target is left untouched.
  ~AtomicFile();

  void write(std::string_view bytes);
  /// Flushes, closes and renames the temporary into place. Idempotent.
  void commit();
  bool committed() const { return committed_; }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::filesystem::path temp_;
  std::FILE* file_ = nullptr;
  int pending_slot_ = -1;
  bool committed_ = false;
};

/// `bytes` into `path` through an AtomicFile: the old file stays until the new one is complete.
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

/// Unlinks the temporary of every AtomicFile of this process that is still open.
/// Async-signal-safe (unlink(2) only), for signal handlers.
void remove_pending_temporaries() noexcept;

/// Installs handlers for SIGINT, SIGTERM, SIGHUP and SIGQUIT that remove the pending temporaries
/// and then end the process by the same signal (the default action), so an interrupted command
/// leaves nothing half-written behind. For programs, not libraries: call once from main().
void remove_temporaries_on_termination();

}  // namespace tpf
