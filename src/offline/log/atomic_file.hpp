// A file that appears complete or not at all: written to a temporary beside the target, renamed
// into place on commit(), removed when dropped uncommitted.
#pragma once

#include <cstdio>
#include <filesystem>
#include <string_view>

namespace tpf::offline {

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
  bool committed_ = false;
};

}  // namespace tpf::offline
