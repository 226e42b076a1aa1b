// `tpf identify`: identify the arm's nominal model from a log and write a parameter file.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "commands.hpp"
#include "heap_reuse.hpp"
#include "joint_dispatch.hpp"
#include "offline/identify/identify.hpp"
#include "offline/identify/joint_samples.hpp"
#include "offline/log/read_logs.hpp"
#include "offline/log/torque_sensor.hpp"
#include "read_command_logs.hpp"
#include "tpf/common/error.hpp"
#include "tpf/model/load_robot.hpp"

namespace {

struct IdentifyArgs {
  std::vector<std::string> logs;
  std::string robot, out;
  double static_velocity = 1e-4;
  bool no_load_friction = false, quiet = false, friction_from_sensor = false;
};

template <int N>
void run(const tpf::offline::Log& log, const IdentifyArgs& a) {
  using namespace tpf::offline;
  const auto start = std::chrono::steady_clock::now();
  IdentifyOptions options;
  options.samples.regimes.static_velocity = a.static_velocity;
  options.fit_load_friction = !a.no_load_friction;
  options.friction_from_sensor = a.friction_from_sensor;
  if (!a.quiet)
    options.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  const auto model = tpf::load_robot<double, N>(a.robot);
  const auto id = identify<N>(log, model, options);
  const auto& s = id.samples;
  std::printf("%s%s: %ld samples (%zu skipped for a missing value), effort in %s\n",
              s.simulated ? "SIMULATED log " : "log ", log.source.c_str(),
              static_cast<long>(s.size()), s.invalid_count, s.units.name());
  std::printf("held-out residual RMSE [%s]     static  static-to-kinetic   moving      all\n",
              s.units.name());
  nlohmann::json fit;
  for (int j = 0; j < N; ++j) {
    const auto& h = id.heldout[j];
    // Fitted in N·m; printed in the log's unit (mA for a log of currents).
    const auto in_log_unit = [&](double tau) { return s.units.to_effort(j, tau); };
    std::printf("  joint %d  %28.3f %18.3f %8.3f %8.3f\n", j + 1,
                in_log_unit(h[Regime::Static].rmse), in_log_unit(h[Regime::StaticToKinetic].rmse),
                in_log_unit(h[Regime::Moving].rmse), in_log_unit(h.valid.rmse));
    fit["heldout_rmse"].push_back({{"static", h[Regime::Static].rmse},
                                   {"static-to-kinetic", h[Regime::StaticToKinetic].rmse},
                                   {"moving", h[Regime::Moving].rmse},
                                   {"all", h.valid.rmse}});
  }
  const std::string held_out_note = nothing_held_out_note(s, options.samples);
  if (!held_out_note.empty()) std::printf("note: %s\n", held_out_note.c_str());
  std::printf("consistency: %s (min eigenvalue of M(q) %.4g kg·m²)\n",
              id.consistency.consistent() ? "ok" : "PROBLEMS", id.consistency.min_mass_eigenvalue);
  for (const auto& p : id.consistency.problems)
    std::printf("  problem: %s\n", p.c_str());
  for (const auto& n : id.friction_notes)
    std::printf("  friction: %s\n", n.c_str());
  fit["friction_notes"] = id.friction_notes;
  if (!held_out_note.empty()) fit["heldout_note"] = held_out_note;
  fit["consistent"] = id.consistency.consistent();
  fit["problems"] = id.consistency.problems;
  fit["simulated"] = s.simulated;
  tpf::save_nominal_model<N>(a.out, id.nominal, log.source, fit.dump());
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("wrote %s (%.1f s)%s\n", a.out.c_str(), wall,
              id.refitted ? ": the model refitted on every sample, the held-out ones included "
                            "(the held-out figures above are of its fit without them)"
                          : "");
}

}  // namespace

namespace tpf::cli {

/// Adds `tpf identify` to the app.
void register_identify_command(CLI::App& app) {
  auto a = std::make_shared<IdentifyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "identify",
      "Identify rigid-body base parameters (with armature) and Stribeck + load-dependent friction "
      "from a log by weighted least squares and Ceres; validate on held-out data (the last file "
      "of several, else every 4th 5 s block), then write the model refitted on every sample");
  cmd->add_option("--log", a->logs,
                  "Log(s) (tpf CSV or .csv.gz; i<j> in mA or tau<j> in N·m); several are read as "
                  "one, each file its own segment")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--robot", a->robot, "Robot file, e.g. data/arm4.robot.json")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", a->out, "Parameter file to write (tpf-params JSON)")->required();
  cmd->add_option("--static-velocity", a->static_velocity, "Static threshold |q̇| [rad/s]")
      ->capture_default_str();
  cmd->add_flag("--no-load-friction", a->no_load_friction, "Keep α_c = α_v = 0");
  cmd->add_flag("--friction-from-sensor", a->friction_from_sensor,
                "Fit each joint's friction against its joint torque sensor (tau_sensor<j>, "
                "where it varies): effort - K*(tau_sensor + Ia*q''), the drive loss behind the "
                "gear, instead of effort - rigid-body prediction");
  cmd->add_flag("--quiet", a->quiet, "No progress lines");
  cmd->callback([a] {
    reuse_freed_memory();
    const offline::Log log = read_command_logs(a->logs);
    with_joint_count(log.joint_count(), log.source, [&]<int N>() { run<N>(log, *a); });
  });
}

}  // namespace tpf::cli
