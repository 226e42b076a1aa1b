// tpf_arm_emulate: an emulated arm on pseudo-terminals (four PH54 on a first-order plant and a
// 16-pad board at 1 kHz) for running tpf_arm_loop without hardware. Results are simulated.
//   tpf_arm_emulate --pads-link /tmp/tpf_pads &   # prints the motor pty path
//   tpf_arm_loop --motors /dev/pts/N --pads /tmp/tpf_pads --duration 5
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <ctime>

#include "dynamixel/emulator/first_order_plant.hpp"
#include "dynamixel/emulator/motor_chain_emulator.hpp"
#include "dynamixel/serial/pty_pair.hpp"
#include "teensy/emulator/pad_board_emulator.hpp"

namespace {
volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) {
  g_stop = 1;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace tpf;
  CLI::App app{"Emulated PH54 chain and pad board on ptys (simulated data)"};
  std::string pads_link = "/tmp/tpf_pads";
  int firmware = 12;
  double duration = 0.0;
  int priority = 0;
  app.add_option("--pads-link", pads_link, "symlink to the pad board's pty");
  app.add_option("--firmware", firmware, "motor firmware version (< 12: no Fast Sync Read)");
  app.add_option("--duration", duration, "seconds to run (0: until Ctrl-C)");
  app.add_option("--priority", priority, "SCHED_FIFO priority of the device threads (0: normal)");
  CLI11_PARSE(app, argc, argv);

  serial::PtyPair motors_pty;
  dxl::emu::FirstOrderPlant plant(4);
  dxl::emu::MotorChainEmulator motors(motors_pty.master(), plant,
                                      dxl::emu::arm_chain(static_cast<std::uint8_t>(firmware)));
  pad::PadBoardEmulatorOptions pad_options{pads_link};
  pad_options.realtime_priority = priority;
  pad::PadBoardEmulator pads(pad_options);
  motors.start(priority);
  pads.start();
  std::printf("motors: %s\npads:   %s\n(simulated devices; Ctrl-C to stop)\n",
              motors_pty.slave_path().c_str(), pads_link.c_str());
  std::fflush(stdout);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const std::time_t start = std::time(nullptr);
  while (!g_stop && (duration <= 0.0 || std::difftime(std::time(nullptr), start) < duration)) {
    const timespec pause{0, 50'000'000};
    clock_nanosleep(CLOCK_MONOTONIC, 0, &pause, nullptr);
  }
  pads.stop();
  motors.stop();
  return 0;
}
