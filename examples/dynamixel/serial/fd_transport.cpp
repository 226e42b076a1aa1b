#include "dynamixel/serial/fd_transport.hpp"

#include <errno.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>

namespace tpf::serial {
namespace {

/// poll() timeout in ms for a deadline, rounded up so that we never wake before it.
int poll_timeout_ms(MonoNs deadline) {
  const MonoNs left = deadline - monotonic_now();
  if (left <= 0) return 0;
  return static_cast<int>(std::min<MonoNs>((left + 999'999) / 1'000'000, 60'000));
}

}  // namespace

FdTransport& FdTransport::operator=(FdTransport&& other) noexcept {
  if (this != &other) {
    close();
    fd_ = other.release();
  }
  return *this;
}

void FdTransport::close() noexcept {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool FdTransport::write(std::span<const std::uint8_t> bytes, MonoNs deadline) {
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) return false;
    pollfd p{fd_, POLLOUT, 0};
    if (::poll(&p, 1, poll_timeout_ms(deadline)) <= 0 || (p.revents & (POLLERR | POLLHUP)))
      return false;
  }
  return true;
}

ReadResult FdTransport::read(std::span<std::uint8_t> out, MonoNs deadline) {
  if (fd_ < 0) return {0, true};
  bool hung_up = false;
  for (;;) {
    // A tty in raw mode with VMIN = VTIME = 0 returns 0 when it has no data, so 0 alone is not
    // EOF: a hang-up shows as POLLHUP/POLLERR (or EIO), then nothing left to read.
    const ssize_t n = ::read(fd_, out.data(), out.size());
    if (n > 0) return {static_cast<std::size_t>(n), false};
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) return {0, true};  // EIO, ENODEV, ...
    if (hung_up) return {0, true};
    const int timeout = poll_timeout_ms(deadline);
    if (timeout == 0 && monotonic_now() >= deadline) return {0, false};
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, timeout);
    if (ready < 0 && errno != EINTR) return {0, true};
    if (ready == 0 && monotonic_now() >= deadline) return {0, false};
    hung_up = (p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0;  // drain what is left first
  }
}

void FdTransport::discard_input() {
  if (fd_ < 0) return;
  if (::isatty(fd_)) {
    ::tcflush(fd_, TCIFLUSH);
    return;
  }
  std::uint8_t sink[256];
  while (::read(fd_, sink, sizeof sink) > 0) {
  }
}

}  // namespace tpf::serial
