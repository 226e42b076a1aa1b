// A log file's text for parsing: a plain file is mapped read-only (the page cache is read in
// place, no copy into the heap), a gzip file is decompressed into memory.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace tpf::offline {

class FileText {
 public:
  /// Throws tpf::Error naming the file when it cannot be opened, read or decompressed.
  explicit FileText(const std::filesystem::path& path);
  ~FileText();
  FileText(const FileText&) = delete;
  FileText& operator=(const FileText&) = delete;

  /// The whole text (decompressed when the file starts with the gzip magic). A mapped file must
  /// not be truncated while it is read.
  std::string_view text() const { return text_; }

 private:
  void unmap();

  void* mapping_ = nullptr;
  std::size_t mapped_bytes_ = 0;
  std::string owned_;  ///< decompressed text, or the bytes of a file that cannot be mapped
  std::string_view text_;
};

}  // namespace tpf::offline
