// Linux serial port for an RS-485 adapter (U2D2 / FTDI) or a USB CDC device (Teensy).
#pragma once

#include <string>

#include "dynamixel/serial/fd_transport.hpp"

namespace tpf::serial {

/// What open_serial_port() did; low latency fails harmlessly on ptys and CDC-ACM devices.
struct SerialPortInfo {
  bool low_latency = false;  ///< ASYNC_LOW_LATENCY accepted (FTDI: latency timer 1 ms)
  bool custom_baud = false;  ///< the rate went through termios2/BOTHER
};

/// Opens `path` O_RDWR|O_NOCTTY|O_NONBLOCK in raw 8N1 mode (c_cflag = CS8|CLOCAL|CREAD,
/// c_iflag = IGNPAR, VMIN = VTIME = 0) at `baud` bit/s: B-constants up to B4000000, any other
/// rate through termios2 with BOTHER. baud = 0 keeps the speed (USB CDC ignores it).
/// Then tries ASYNC_LOW_LATENCY (TIOCSSERIAL) and flushes the input.
/// Throws tpf::Error naming the path on failure.
FdTransport open_serial_port(const std::string& path, int baud, SerialPortInfo* info = nullptr);

}  // namespace tpf::serial
