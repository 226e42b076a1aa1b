#include "offline/log/file_text.hpp"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "offline/log/gzip.hpp"
#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

/// Closes a file descriptor when it goes out of scope.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

Error file_error(const std::filesystem::path& path, const std::string& what) {
  return Error::at(path.string(), 0, "", what + ": " + std::strerror(errno));
}

/// Reads the rest of `fd` into `out` (a file that cannot be mapped, e.g. a pipe).
void read_all(const std::filesystem::path& path, int fd, std::string& out) {
  char buffer[1 << 16];
  while (true) {
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got == 0) return;
    if (got < 0) {
      if (errno == EINTR) continue;
      throw file_error(path, "read failed");
    }
    out.append(buffer, static_cast<std::size_t>(got));
  }
}

}  // namespace

FileText::FileText(const std::filesystem::path& path) : path_(path) {
  const Descriptor file{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (file.fd < 0) throw file_error(path, "cannot open");
  struct stat status {};
  if (::fstat(file.fd, &status) != 0) throw file_error(path, "cannot read size");
  const bool regular = S_ISREG(status.st_mode);
  if (regular && status.st_size > 0) map(file.fd, static_cast<std::size_t>(status.st_size));
  if (mapping_ == nullptr && (!regular || status.st_size > 0)) {
    read_all(path, file.fd, owned_);
    text_ = owned_;
  }
  if (!is_gzip(text_)) return;
  try {
    owned_ = gunzip(text_, path.string());
  } catch (...) {
    unmap();
    check_complete();  // a truncation, not a corrupt file, if the file shrank
    throw;
  }
  unmap();
  check_complete();
  text_ = owned_;
}

void FileText::map(int fd, std::size_t bytes) {
  void* mapping = ::mmap(nullptr, bytes, PROT_READ, MAP_PRIVATE, fd, 0);
  if (mapping == MAP_FAILED) throw file_error(path_, "cannot map");
  if (!truncation_guard_.watch(mapping, bytes)) {  // too many files mapped: read this one
    ::munmap(mapping, bytes);
    return;
  }
  mapping_ = mapping;
  mapped_bytes_ = bytes;
  ::madvise(mapping_, mapped_bytes_, MADV_WILLNEED);  // read ahead a file not yet cached
  text_ = std::string_view(static_cast<const char*>(mapping_), mapped_bytes_);
}

void FileText::check_complete() const {
  if (!truncated_ && !truncation_guard_.truncated()) return;
  std::error_code error;
  const auto now = std::filesystem::file_size(path_, error);
  throw Error::at(path_.string(), 0, "",
                  "the file shrank from " + std::to_string(mapped_bytes_) + " to " +
                      (error ? std::string("?") : std::to_string(now)) +
                      " bytes while it was read (another program truncated or rewrote it); "
                      "nothing was read from it: read it again once it is complete");
}

void FileText::unmap() {
  truncated_ = truncated_ || truncation_guard_.truncated();
  truncation_guard_.unwatch();
  if (mapping_ != nullptr) ::munmap(mapping_, mapped_bytes_);
  mapping_ = nullptr;
}

FileText::~FileText() {
  unmap();
}

}  // namespace tpf::offline
