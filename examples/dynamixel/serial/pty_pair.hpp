// A pseudo-terminal standing in for a USB serial device: the emulator owns the master side, the
// host opens the slave path exactly as it would open /dev/ttyUSB0.
#pragma once

#include <string>

#include "dynamixel/serial/fd_transport.hpp"

namespace tpf::serial {

/// openpty() in raw mode. The master is non-blocking. The pair also keeps one slave descriptor
/// open so the master never sees a hang-up while no host is attached.
class PtyPair {
 public:
  /// Throws tpf::Error when no pty can be allocated.
  PtyPair();
  ~PtyPair();
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  /// The device side (what the emulated device writes, the host reads).
  FdTransport& master() noexcept { return master_; }
  /// Path of the slave, e.g. "/dev/pts/7", for the host to open.
  const std::string& slave_path() const noexcept { return slave_path_; }
  /// "Unplugs" the device: closes both sides; the host's reads fail with EIO.
  void close() noexcept;

 private:
  FdTransport master_;
  int slave_hold_ = -1;
  std::string slave_path_;
};

}  // namespace tpf::serial
