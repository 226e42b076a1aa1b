#include "offline/log/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <system_error>

#include "tpf/common/error.hpp"

namespace tpf::offline {
namespace {

std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::string name = ".";
  name.append(path.filename().string()).append(".tmp.").append(std::to_string(::getpid()));
  name.append(".").append(std::to_string(counter++));
  return path.parent_path() / name;
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path path)
    : path_(std::move(path)), temp_(temporary_beside(path_)) {
  if (path_.filename().empty()) throw Error::at(path_.string(), 0, "", "not a file path");
  file_ = std::fopen(temp_.c_str(), "wb");
  if (file_ == nullptr)
    throw Error::at(path_.string(), 0, "", std::string("cannot create: ") + std::strerror(errno));
}

AtomicFile::~AtomicFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
  }
}

void AtomicFile::write(std::string_view bytes) {
  if (file_ == nullptr) throw Error::at(path_.string(), 0, "", "write after commit");
  if (std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size())
    throw Error::at(path_.string(), 0, "", std::string("write failed: ") + std::strerror(errno));
}

void AtomicFile::commit() {
  if (committed_) return;
  const bool flushed = std::fflush(file_) == 0;
  const int flush_errno = errno;
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  if (!flushed || !closed)
    throw Error::at(path_.string(), 0, "",
                    std::string("write failed: ") + std::strerror(flushed ? errno : flush_errno));
  std::error_code ec;
  std::filesystem::rename(temp_, path_, ec);
  if (ec)
    throw Error::at(path_.string(), 0, "", "cannot rename temporary into place: " + ec.message());
  committed_ = true;
}

}  // namespace tpf::offline
