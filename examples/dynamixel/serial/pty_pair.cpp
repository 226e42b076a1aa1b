#include "dynamixel/serial/pty_pair.hpp"

#include <errno.h>
#include <fcntl.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <cstring>

#include "tpf/common/error.hpp"

namespace tpf::serial {

PtyPair::PtyPair() {
  int master = -1;
  int slave = -1;
  char name[128] = {};
  termios raw{};
  cfmakeraw(&raw);
  if (::openpty(&master, &slave, name, &raw, nullptr) != 0)
    throw Error::at("openpty", 0, "", std::strerror(errno));
  ::fcntl(master, F_SETFL, ::fcntl(master, F_GETFL) | O_NONBLOCK);
  ::fcntl(master, F_SETFD, FD_CLOEXEC);
  ::fcntl(slave, F_SETFD, FD_CLOEXEC);
  master_ = FdTransport(master);
  slave_hold_ = slave;
  slave_path_ = name;
}

PtyPair::~PtyPair() {
  close();
}

void PtyPair::close() noexcept {
  master_.close();
  if (slave_hold_ >= 0) ::close(slave_hold_);
  slave_hold_ = -1;
}

}  // namespace tpf::serial
