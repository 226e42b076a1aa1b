// tpf_arm_loop: runs the 400 Hz loop on the real arm (or on tpf_arm_emulate's ptys) with the core
// Estimator, writes a tpf CSV log and prints loop and estimator statistics.
//   tpf_arm_loop --motors /dev/ttyUSB0 --pads /dev/ttyACM0 --hold --duration 60 --log run.csv
#include <CLI/CLI.hpp>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>

#include "arm/arm_loop.hpp"
#include "arm/realtime.hpp"
#include "arm/report_printer.hpp"
#include "dynamixel/ph54/chain_setup.hpp"
#include "dynamixel/serial/serial_port.hpp"
#include "tpf/common/error.hpp"

namespace {

tpf::arm::ArmLoop* g_loop = nullptr;
extern "C" void on_signal(int) {
  if (g_loop != nullptr) g_loop->request_stop();
}

/// A shipped data file: $TPF_DATA_DIR/name if set, else the source tree's data/name.
std::string data_file(const std::string& name) {
  const char* dir = std::getenv("TPF_DATA_DIR");
  return std::string(dir != nullptr && *dir != '\0' ? dir : TPF_ARM_DATA_DIR) + "/" + name;
}

/// The recording's '# key: value' lines.
tpf::offline::LogMetadata log_metadata(double rate_hz, const std::string& note) {
  tpf::offline::LogMetadata meta;
  std::ostringstream rate;
  rate << rate_hz;
  meta.set("robot", "arm4");
  meta.set("rate_hz", rate.str());
  meta.set("source", "recorded on the arm (tpf_arm_loop)");
  meta.set("note", note);
  return meta;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tpf;
  CLI::App app{
      "400 Hz loop of the PH54 arm with the pad board: reads the motors and pads, runs the tpf "
      "estimator (external joint torques, contact force) on every cycle, logs and reports.\n"
      "The estimator is built from a parameter file (tpf identify/diagnose), the robot and pad "
      "layout files, an estimator parameter file (tpf calibrate, from a contact-free log of this "
      "arm) and friction-network weights (tpf train); defaults are the project's data/ files for "
      "the arm4 (data/arm4.estimator.json is calibrated on a SIMULATED log: calibrate yours). Its "
      "input is the motor current in mA: hold the arm (--hold) or "
      "excite it (--excite) so the drives carry the load; with torque off the currents are 0."};
  arm::EstimatorFiles est;
  est.params = data_file("arm4.params.json");
  est.robot = data_file("arm4.robot.json");
  est.pads = data_file("arm4.pads.json");
  est.estimator = data_file("arm4.estimator.json");
  est.weights = data_file("weights/arm4.tcn.json");
  bool no_estimator = false, hold = false;
  std::string motors_path, pads_path, log_path, note = "recorded by tpf_arm_loop";
  int baud = 4'000'000, set_baud_from = 0, priority = 80;
  std::vector<int> ids{1, 2, 3, 4};
  double rate = 400.0, duration = 10.0, excite = 0.0, margin_ms = 1.0;
  int watchdog = 5;
  app.add_option("--motors", motors_path, "RS-485 adapter (U2D2), e.g. /dev/ttyUSB0")->required();
  app.add_option("--pads", pads_path, "pad board, e.g. /dev/ttyACM0 or a udev symlink");
  app.add_option("--baud", baud, "bus rate in bit/s (motors must already use it)");
  app.add_option("--set-baud-from", set_baud_from,
                 "open at this rate first and switch the motors to --baud");
  app.add_option("--ids", ids, "motor IDs in chain order")
      ->delimiter(',')
      ->check(CLI::Range(0, 252));
  app.add_option("--rate", rate, "loop rate [Hz]")->check(CLI::Range(1.0, 2000.0));
  app.add_option("--duration", duration, "seconds to run (0: until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--log", log_path, "CSV log to write (tpf log format v1)");
  app.add_option("--note", note, "free text for the log's '# note:'");
  app.add_option("--excite", excite, "multisine amplitude [rad] in position mode; 0: torque off")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--watchdog", watchdog, "bus watchdog in 20 ms units (0 disables)")
      ->check(CLI::Range(0, 127));
  app.add_option("--timeout-margin", margin_ms, "extra response timeout [ms]");
  app.add_option("--priority", priority, "SCHED_FIFO priority");
  app.add_flag("--hold", hold,
               "position mode, goal = the pose read at start, torque on: the drives hold the arm");
  app.add_flag("--no-estimator", no_estimator, "only read, log and report");
  app.add_option(
         "--params", est.params,
         "nominal model (tpf-params, N*m; the currents are converted with the robot file's K_t)")
      ->capture_default_str();
  app.add_option("--robot", est.robot, "robot file of the parameters")->capture_default_str();
  app.add_option("--pad-layout", est.pads, "pad layout (tpf-pads); pad k = board channel k")
      ->capture_default_str();
  app.add_option("--weights", est.weights,
                 "friction network: an all-joints weight file, or a path whose "
                 "<stem>.joint1..4.json exist (one network per joint); 'none': no compensator")
      ->capture_default_str();
  app.add_option("--estimator", est.estimator,
                 "estimator parameters (tpf-estimator): dead bands, noise levels, thresholds, pad "
                 "gain; write one with `tpf calibrate --log <contact-free log of this arm>`")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    if (ids.empty() || ids.size() > arm::kMaxJoints)
      throw Error::at("--ids", 0, "",
                      "give 1 to " + std::to_string(arm::kMaxJoints) + " motor IDs");
    if (hold && excite > 0.0) throw Error::at("--hold", 0, "", "use --hold or --excite, not both");
    // Files first: a bad file stops the program before it touches the motors.
    std::unique_ptr<arm::EstimatorHook> estimator;
    if (!no_estimator) {
      if (ids.size() != static_cast<std::size_t>(arm::EstimatorHook::kJoints))
        throw Error::at("--ids", 0, "", "the estimator is built for the 4-joint arm4: give 4 IDs");
      if (rate != 400.0)
        throw Error::at("--rate", 0, "",
                        "the estimator's filters and friction networks are set for 400 Hz "
                        "(use --no-estimator for other rates)");
      if (est.weights == "none") est.weights.clear();
      estimator = std::make_unique<arm::EstimatorHook>(est);
      std::printf("%s\n", estimator->description().c_str());
    }
    std::vector<std::uint8_t> id_bytes;
    id_bytes.reserve(ids.size());
    for (const int id : ids)
      id_bytes.push_back(static_cast<std::uint8_t>(id));
    const dxl::BusTiming timing{baud, 1.0, margin_ms};
    if (set_baud_from > 0) {
      serial::FdTransport slow = serial::open_serial_port(motors_path, set_baud_from);
      dxl::Bus bus(slow, dxl::BusTiming{set_baud_from, 1.0, 100.0});
      dxl::ph54::set_torque(bus, id_bytes, false);
      const auto code = baud == 4'000'000   ? dxl::ph54::BaudCode::b4M
                        : baud == 2'000'000 ? dxl::ph54::BaudCode::b2M
                        : baud == 1'000'000
                            ? dxl::ph54::BaudCode::b1M
                            : throw Error::at("--baud", 0, "", "use 1000000, 2000000 or 4000000");
      dxl::ph54::write_baud_rate(bus, id_bytes, code);
    }
    serial::SerialPortInfo port_info;
    serial::FdTransport port = serial::open_serial_port(motors_path, baud, &port_info);
    if (!port_info.low_latency)
      std::fprintf(
          stderr,
          "note: ASYNC_LOW_LATENCY not set on %s (set the FTDI latency_timer to 1 via udev)\n",
          motors_path.c_str());
    dxl::Bus bus(port, dxl::BusTiming{baud, 1.0, 100.0});  // start-up: generous timeouts
    dxl::ph54::ChainConfig config;
    config.ids = id_bytes;
    config.bus_watchdog_20ms = static_cast<std::uint8_t>(watchdog);
    config.mode = excite > 0.0 || hold ? dxl::ph54::OperatingMode::position
                                       : dxl::ph54::OperatingMode::current;
    const dxl::ph54::ChainInfo chain = dxl::ph54::set_up_chain(bus, config);
    for (const auto& m : chain.motors)
      std::printf("motor id %u: model %u, firmware %u\n", m.id, m.model, m.firmware);
    std::printf("per-cycle read: %s (574, 10 bytes)\n",
                chain.fast_sync_read ? "Fast Sync Read" : "Sync Read (firmware < 12)");

    std::unique_ptr<pad::PadReader> pads;
    if (!pads_path.empty()) {
      pads = std::make_unique<pad::PadReader>(pad::PadReaderOptions{pads_path});
      pads->start();
    }
    // The log's pads are the layout's (p<k> = pad k of the layout) when the estimator runs.
    const std::size_t log_pads = !pads ? 0 : estimator ? arm::EstimatorHook::kPads : 16;
    std::unique_ptr<arm::LogRecorder> log;
    if (!log_path.empty())
      log = std::make_unique<arm::LogRecorder>(
          log_path, arm::RecordedColumns{id_bytes.size(), log_pads, estimator != nullptr},
          log_metadata(rate, note));
    dxl::ph54::ChainStateReader reader(bus, id_bytes, chain.fast_sync_read);
    arm::ArmLoopOptions options;
    options.rate_hz = rate;
    options.cycles = duration > 0.0 ? static_cast<std::uint64_t>(duration * rate) : 0;
    options.excitation_rad = excite;
    arm::ArmLoop loop(bus, reader, id_bytes, pads.get(), log.get(), options, estimator.get());

    std::string rt_message;
    arm::enter_realtime(priority, rt_message);
    std::printf("%s\n", rt_message.c_str());
    // Torque on last: from here the bus watchdog (100 ms) expects the loop's reads. Goal =
    // present position first, so torque-on never jumps to a goal left from an earlier run;
    // the excitation ramps in from that pose.
    if (excite > 0.0 || hold) dxl::ph54::hold_present_position(bus, id_bytes);
    bus.set_timing(timing);  // in the loop: wire time + 1 ms USB turnaround + margin
    g_loop = &loop;
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    loop.run();
    g_loop = nullptr;
    if (excite > 0.0 || hold) dxl::ph54::set_torque(bus, id_bytes, false);
    if (pads) pads->stop();
    if (log) log->close();
    arm::print_report(stdout, loop.report(), id_bytes.size());
  } catch (const Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
