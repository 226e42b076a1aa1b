// `tpf simulate`: run the digital twin on a scenario file and write a log in the project format.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/sim/scenario.hpp"
#include "offline/sim/simulate.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace {

struct SimulateOptions {
  std::string scenario;
  std::string robot;
  std::uint64_t seed = 1;
  double duration = 0.0;
  std::string out;
  bool quiet = false;
};

void run_simulate(const SimulateOptions& o) {
  const auto scenario = tpf::offline::load_scenario(o.scenario, o.robot);
  const double duration = o.duration > 0 ? o.duration : scenario.duration_s;
  const auto start = std::chrono::steady_clock::now();
  // On a terminal the line is redrawn in place; into a file or a pipe (CI, `2> log`) a line is
  // written at every tenth of the run instead of one per simulated second.
  const bool terminal = ::isatty(STDERR_FILENO) == 1;
  int last_tenth = -1;
  tpf::offline::ProgressSink progress;
  if (!o.quiet) {
    progress = [&](double fraction) {
      const int tenth = static_cast<int>(10.0 * fraction);
      if (!terminal && tenth == last_tenth) return;
      last_tenth = tenth;
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "%ssimulate: %5.1f%%  %7.1f / %.1f s simulated  %6.1f s wall%s",
                   terminal ? "\r" : "", 100.0 * fraction, fraction * duration, duration, wall,
                   terminal ? "" : "\n");
      std::fflush(stderr);
    };
  }
  const auto summary = tpf::offline::simulate_to_file(scenario, o.seed, duration, o.out, progress);
  if (!o.quiet)
    std::fprintf(stderr,
                 "%ssimulate: %s, %d joints, %s: wrote %zu rows (%zu cycles dropped on purpose) to "
                 "%s\n",
                 terminal ? "\n" : "", scenario.robot_file.c_str(), scenario.joints,
                 scenario.pads_file.empty() ? "no skin" : scenario.pads_file.c_str(), summary.rows,
                 summary.dropped_rows, o.out.c_str());
}

}  // namespace

namespace tpf::cli {

/// Adds `tpf simulate` to the app.
void register_simulate_command(CLI::App& app) {
  auto options = std::make_shared<SimulateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Run the digital twin on a scenario and write a log with gt_* ground truth");
  cmd->footer(
      "Run the digital twin (arm of any joint count, drive cascades, friction with memory, "
      "sensors, pads, contacts) on a scenario and write a simulated log with gt_* ground truth"
      "\nExample: tpf simulate --scenario data/scenarios/static-contacts.json --seed 1 --duration "
      "60 --out contacts.csv");
  cmd->add_option("--scenario", options->scenario,
                  "Scenario file, e.g. data/scenarios/excitation.json; it names its robot "
                  "(\"robot\", default data/arm4.robot.json)")
      ->required()
      ->check(input_file());
  cmd->add_option("--robot", options->robot,
                  "Robot file to simulate instead of the scenario's, e.g. data/bench1.robot.json "
                  "(its pads and friction file come with it; the scenario's per-joint vectors "
                  "must then fit its joint count or be left out)")
      ->check(input_file());
  cmd->add_option("--seed", options->seed, "Random seed; the same seed gives the same log")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_option("--duration", options->duration,
                  "Simulated time in seconds (default: the scenario's duration_s)")
      ->check(positive(kMaxSimulatedSeconds));
  cmd->add_option("--out", options->out, "Output log (CSV, tpf log format)")->required();
  cmd->add_flag("--quiet", options->quiet, "No progress line");
  cmd->callback([options] {
    refuse_overwriting_inputs("simulate",
                              {{"--scenario", options->scenario}, {"--robot", options->robot}},
                              {{"--out", options->out}});
    run_simulate(*options);
  });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
