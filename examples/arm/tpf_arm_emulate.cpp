// tpf_arm_emulate: an emulated arm on pseudo-terminals for running tpf_arm_loop without hardware.
// By default four PH54 motors run the digital twin (rigid-body arm, LuGre friction, the PH54
// drive cascade) of a scenario, and the pad board streams the same twin's pad pressures at 1 kHz,
// so a static-contacts scenario's hand pushes show up in both the currents and the pads.
// `--plant first-order` runs the simple first-order plant and synthetic pads instead.
// Everything it produces is simulated.
//   tpf_arm_emulate --pads-link /tmp/tpf_pads &   # prints the motor pty path
//   tpf_arm_loop --motors /dev/pts/N --pads /tmp/tpf_pads --hold --duration 20
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <memory>

#include "dynamixel/emulator/first_order_plant.hpp"
#include "dynamixel/emulator/motor_chain_emulator.hpp"
#include "dynamixel/serial/pty_pair.hpp"
#include "offline/common/data_files.hpp"
#include "offline/sim/scenario.hpp"
#include "teensy/emulator/pad_board_emulator.hpp"
#include "tpf/common/error.hpp"
#include "twin/twin_motor_plant.hpp"

namespace {
volatile std::sig_atomic_t g_stop = 0;
extern "C" void on_signal(int) {
  g_stop = 1;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace tpf;
  CLI::App app{
      "Emulated PH54 chain and pad board on ptys, driven by the tpf digital twin (simulated "
      "data). The motors obey what the host writes (torque, operating mode, goals); the "
      "scenario's hand pushes on the pads whatever pose the host holds."};
  std::string pads_link = "/tmp/tpf_pads";
  std::string plant_kind = "twin";
  std::string scenario_path = offline::data_file("scenarios/static-contacts.json").string();
  std::uint64_t seed = 1;
  int firmware = 12;
  double duration = 0.0;
  int priority = 0;
  app.add_option("--pads-link", pads_link, "symlink to the pad board's pty")->capture_default_str();
  app.add_option("--plant", plant_kind,
                 "twin: the digital twin and its pads; first-order: independent first-order "
                 "joints and synthetic pads (2 + sin(pi t + k) kPa)")
      ->check(CLI::IsMember({"twin", "first-order"}))
      ->capture_default_str();
  app.add_option("--scenario", scenario_path,
                 "twin scenario (robot, friction, drive, sensors; a static-contacts scenario "
                 "also scripts the hand's pushes on the pads)")
      ->capture_default_str();
  app.add_option("--seed", seed, "seed of the twin's noise and push script")->capture_default_str();
  app.add_option("--firmware", firmware, "motor firmware version (< 12: no Fast Sync Read)");
  app.add_option("--duration", duration, "seconds to run (0: until Ctrl-C)");
  app.add_option("--priority", priority, "SCHED_FIFO priority of the device threads (0: normal)");
  CLI11_PARSE(app, argc, argv);

  try {
    std::unique_ptr<dxl::emu::MotorPlant> plant;
    pad::PadBoardEmulatorOptions pad_options;
    pad_options.link_path = pads_link;
    pad_options.realtime_priority = priority;
    if (plant_kind == "twin") {
      const offline::Scenario scenario = offline::load_scenario(scenario_path);
      auto twin = std::make_unique<dxl::emu::TwinMotorPlant>(
          scenario, dxl::emu::TwinMotorPlantOptions{seed, 0});
      pad_options.source = [p = twin.get()](std::span<float> kpa) { return p->pad_pressures(kpa); };
      std::printf("twin: %s (seed %llu), %d pads\n", scenario.name.c_str(),
                  static_cast<unsigned long long>(seed), twin->pad_count());
      plant = std::move(twin);
    } else {
      plant = std::make_unique<dxl::emu::FirstOrderPlant>(4);
    }
    serial::PtyPair motors_pty;
    dxl::emu::MotorChainEmulator motors(motors_pty.master(), *plant,
                                        dxl::emu::arm_chain(static_cast<std::uint8_t>(firmware)));
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
  } catch (const Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
