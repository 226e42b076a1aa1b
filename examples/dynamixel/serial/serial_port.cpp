#include "dynamixel/serial/serial_port.hpp"

#include <asm/termbits.h>  // termios2, BOTHER, TCGETS2/TCSETS2
#include <errno.h>
#include <fcntl.h>
#include <linux/serial.h>  // serial_struct, ASYNC_LOW_LATENCY
#include <sys/ioctl.h>
#include <unistd.h>

#include <cstring>

#include "tpf/common/error.hpp"

namespace tpf::serial {
namespace {

// <asm/termbits.h> and <termios.h> cannot be included together, so this file talks to the tty
// with ioctl() only: TCGETS2/TCSETS2 cover every rate, standard or not.

/// Standard Bxxx constant for a rate, or 0 when only BOTHER can express it.
speed_t standard_speed(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
    case 460800:
      return B460800;
    case 500000:
      return B500000;
    case 576000:
      return B576000;
    case 921600:
      return B921600;
    case 1000000:
      return B1000000;
    case 1152000:
      return B1152000;
    case 1500000:
      return B1500000;
    case 2000000:
      return B2000000;
    case 2500000:
      return B2500000;
    case 3000000:
      return B3000000;
    case 3500000:
      return B3500000;
    case 4000000:
      return B4000000;
    default:
      return 0;
  }
}

[[noreturn]] void fail(const std::string& path, const char* what) {
  throw Error::at(path, 0, what, std::strerror(errno));
}

}  // namespace

FdTransport open_serial_port(const std::string& path, int baud, SerialPortInfo* info) {
  FdTransport port(::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC));
  if (!port.is_open()) fail(path, "open");

  termios2 tio{};
  if (::ioctl(port.fd(), TCGETS2, &tio) != 0) fail(path, "TCGETS2");
  const speed_t keep = tio.c_cflag & (CBAUD | (CBAUD << IBSHIFT));
  tio.c_iflag = IGNPAR;
  tio.c_oflag = 0;
  tio.c_lflag = 0;
  tio.c_cflag = CS8 | CLOCAL | CREAD;
  tio.c_cc[VMIN] = 0;
  tio.c_cc[VTIME] = 0;
  bool custom = false;
  if (baud <= 0) {
    tio.c_cflag |= keep;
  } else if (const speed_t code = standard_speed(baud); code != 0) {
    tio.c_cflag |= code;  // e.g. B4000000: 4 Mbps, exact on the U2D2
  } else {
    tio.c_cflag |= BOTHER | (BOTHER << IBSHIFT);
    tio.c_ispeed = tio.c_ospeed = static_cast<speed_t>(baud);
    custom = true;
  }
  if (::ioctl(port.fd(), TCSETS2, &tio) != 0) fail(path, "TCSETS2 (baud rate)");

  // FTDI: ASYNC_LOW_LATENCY sets the latency timer to 1 ms. ptys and cdc_acm refuse: harmless.
  serial_struct ss{};
  bool low_latency = false;
  if (::ioctl(port.fd(), TIOCGSERIAL, &ss) == 0) {
    ss.flags |= ASYNC_LOW_LATENCY;
    low_latency = ::ioctl(port.fd(), TIOCSSERIAL, &ss) == 0;
  }
  ::ioctl(port.fd(), TCFLSH, TCIFLUSH);
  if (info != nullptr) *info = SerialPortInfo{low_latency, custom};
  return port;
}

}  // namespace tpf::serial
