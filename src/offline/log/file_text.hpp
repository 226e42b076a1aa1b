// A log file's text for parsing: a plain file is mapped read-only (the page cache is read in
// place, no copy into the heap), a gzip file is decompressed into memory. A mapped file that
// another program truncates while it is read is reported, not a crash (TruncationGuard).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "offline/log/truncation_guard.hpp"

namespace tpf::offline {

class FileText {
 public:
  /// Throws tpf::Error naming the file when it cannot be opened, read or decompressed.
  explicit FileText(const std::filesystem::path& path);
  ~FileText();
  FileText(const FileText&) = delete;
  FileText& operator=(const FileText&) = delete;

  /// The whole text (decompressed when the file starts with the gzip magic). Where the file was
  /// truncated while mapped, the bytes past its new end read as zeros: call check_complete().
  std::string_view text() const { return text_; }

  /// Throws tpf::Error naming the file if it shrank while its text was read (another program
  /// truncated or rewrote it), so that what was parsed from text() is not the file's.
  void check_complete() const;

 private:
  /// Maps the file's `bytes` and watches the mapping; leaves mapping_ null (the caller reads
  /// the file) when no watch is free.
  void map(int fd, std::size_t bytes);
  void unmap();

  std::filesystem::path path_;
  TruncationGuard truncation_guard_;
  bool truncated_ = false;  ///< the file shrank while mapped (kept after unmap)
  void* mapping_ = nullptr;
  std::size_t mapped_bytes_ = 0;
  std::string owned_;  ///< decompressed text, or the bytes of a file that cannot be mapped
  std::string_view text_;
};

}  // namespace tpf::offline
