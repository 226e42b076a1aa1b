#include "core/common/atomic_file.hpp"

#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <string>
#include <system_error>

#include "tpf/common/error.hpp"

namespace tpf {
namespace {

/// Temporaries still open, readable from a signal handler: fixed slots, claimed and released
/// with atomics, paths copied in before the slot is published.
struct PendingTemporary {
  std::atomic<bool> claimed{false};
  std::atomic<bool> published{false};
  char path[PATH_MAX] = {};
};
std::array<PendingTemporary, 64> pending;

/// Slot index, or -1 when every slot is taken or the path is too long (the temporary is then
/// still removed by the destructor, only not by a signal handler).
int publish_pending(const std::filesystem::path& temp) {
  const std::string& text = temp.native();
  if (text.size() >= PATH_MAX) return -1;
  for (int i = 0; i < static_cast<int>(pending.size()); ++i) {
    bool expected = false;
    if (!pending[i].claimed.compare_exchange_strong(expected, true)) continue;
    std::memcpy(pending[i].path, text.c_str(), text.size() + 1);
    pending[i].published.store(true);
    return i;
  }
  return -1;
}

void withdraw_pending(int slot) {
  if (slot < 0) return;
  pending[slot].published.store(false);
  pending[slot].claimed.store(false);
}

std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  static std::atomic<unsigned> counter{0};
  std::string name = ".";
  name.append(path.filename().string()).append(".tmp.").append(std::to_string(::getpid()));
  name.append(".").append(std::to_string(counter++));
  return path.parent_path() / name;
}

extern "C" void remove_temporaries_and_terminate(int signal) {
  remove_pending_temporaries();
  // SA_RESETHAND restored the default action: end the process by the same signal.
  ::raise(signal);
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path path)
    : path_(std::move(path)), temp_(temporary_beside(path_)) {
  if (path_.filename().empty()) throw Error::at(path_.string(), 0, "", "not a file path");
  pending_slot_ = publish_pending(temp_);
  file_ = std::fopen(temp_.c_str(), "wb");
  if (file_ == nullptr) {
    withdraw_pending(pending_slot_);
    throw Error::at(path_.string(), 0, "", std::string("cannot create: ") + std::strerror(errno));
  }
}

AtomicFile::~AtomicFile() {
  if (file_ != nullptr) std::fclose(file_);
  if (!committed_) {
    std::error_code ignored;
    std::filesystem::remove(temp_, ignored);
  }
  withdraw_pending(pending_slot_);
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
  withdraw_pending(pending_slot_);
  pending_slot_ = -1;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  AtomicFile file(path);
  file.write(bytes);
  file.commit();
}

void remove_pending_temporaries() noexcept {
  for (PendingTemporary& p : pending)
    if (p.published.load()) ::unlink(p.path);
}

void remove_temporaries_on_termination() {
  struct sigaction action {};
  action.sa_handler = remove_temporaries_and_terminate;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  for (int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT})
    ::sigaction(signal, &action, nullptr);
}

}  // namespace tpf
