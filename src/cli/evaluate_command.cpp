// `tpf evaluate`: tactile-only, proprioceptive-only and fusion side by side on held-out logs.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "core/common/atomic_file.hpp"
#include "model_file_options.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/evaluate/evaluation.hpp"
#include "offline/evaluate/evaluation_report.hpp"
#include "offline/log/read_log.hpp"
#include "offline/regimes/regime_stats.hpp"
#include "offline/report/text_table.hpp"
#include "offline/sim/scenario.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"
#include "read_command_logs.hpp"
#include "tpf/estimation/load_estimator.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace {

struct EvaluateCommandOptions {
  tpf::cli::ModelFiles model;
  std::string weights, calibration, contacts, teaching, out;
  std::vector<std::string> excitation;
  std::string teaching_scenario;
  std::uint64_t teaching_seed = 5;
  double teaching_duration = 60.0;
  bool quiet = false, verbose = false;
};

bool is_simulated(const tpf::offline::Log& log) {
  const auto source = log.meta.get("source");
  return source && source->find("simulated") != std::string::npos;
}

/// Refuses a report or JSON file in --out that is one of the input files.
void refuse_colliding_outputs(const EvaluateCommandOptions& o) {
  using namespace tpf::cli;
  const PathOptions logs =
      joined(joined({{"--calibration", o.calibration}}, each_of("--excitation", o.excitation)),
             {{"--contacts", o.contacts},
              {"--teaching", o.teaching},
              {"--teaching-scenario", o.teaching_scenario}});
  const std::filesystem::path out(o.out);
  refuse_overwriting_inputs(
      "evaluate", joined(joined(model_inputs(o.model), weight_files("--weights", o.weights)), logs),
      {{"--out", (out / "evaluate.html").string()}, {"--out", (out / "evaluation.json").string()}});
}

/// Table I per joint (--verbose): RMSE nominal -> with the TCN and the change, per regime.
void print_per_joint_table(const tpf::offline::Evaluation& ev) {
  using namespace tpf::offline;
  Table table;
  table.header = {"joint"};
  for (const Regime g : {Regime::Static, Regime::StaticToKinetic, Regime::Moving})
    table.header.push_back(std::string(regime_name(g)) + " [" + ev.units.name() + "]");
  for (int j = 0; j < ev.joints; ++j) {
    std::vector<std::string> row{std::to_string(j + 1)};
    for (const Regime g : {Regime::Static, Regime::StaticToKinetic, Regime::Moving}) {
      char cell[80] = "-";
      for (const ResidualRow& r : ev.table)
        if (r.joint == j && r.regime == g)
          std::snprintf(cell, sizeof cell, "%.1f -> %.1f (%+.0f %%)", r.nominal.rmse,
                        r.compensated.rmse, percent_change(r.nominal.rmse, r.compensated.rmse));
      row.emplace_back(cell);
    }
    table.rows.push_back(std::move(row));
  }
  std::printf("  per joint, RMSE nominal -> TCN (change):\n%s", table_text(table).c_str());
}

void run_evaluate(const EvaluateCommandOptions& o) {
  using namespace tpf::offline;
  const auto say = [&](const std::string& line) {
    if (!o.quiet) std::fprintf(stderr, "%s\n", line.c_str());
  };
  ReplaySetup setup = tpf::cli::load_model_setup(o.model, o.weights);

  say("evaluate: reading logs");
  const Log calibration = tpf::cli::read_replayed_log(o.calibration, o.quiet);
  std::vector<Log> excitation;
  for (const std::string& p : o.excitation)
    excitation.push_back(tpf::cli::read_replayed_log(p, o.quiet));
  const Log contacts =
      o.contacts.empty() ? Log{} : tpf::cli::read_replayed_log(o.contacts, o.quiet);
  const Log teaching =
      o.teaching.empty() ? Log{} : tpf::cli::read_replayed_log(o.teaching, o.quiet);
  setup.parameters = estimator_parameters_from_noise(
      estimate_sensor_noise(calibration, setup.nominal.model.torque_constant));

  EvaluationLogs logs;
  logs.calibration = &calibration;
  bool simulated = is_simulated(calibration);
  for (const Log& l : excitation) {
    logs.excitation.push_back(&l);
    simulated = simulated || is_simulated(l);
  }
  if (!o.contacts.empty()) logs.contacts = &contacts;
  if (!o.teaching.empty()) logs.teaching = &teaching;
  Scenario scenario;
  if (!o.teaching_scenario.empty()) {
    scenario = load_scenario(o.teaching_scenario);
    logs.teaching_scenario = &scenario;
    logs.teaching_seed = o.teaching_seed;
    logs.teaching_duration_s = o.teaching_duration;
  }
  const Evaluation ev = evaluate(setup, logs, say);

  std::filesystem::create_directories(o.out);
  std::vector<std::string> notes{"nominal model: " + o.model.params,
                                 "compensator: " + (o.weights.empty() ? "none" : o.weights),
                                 "calibration log (dead bands): " + o.calibration};
  for (const std::string& p : o.excitation)
    notes.push_back("held-out excitation log: " + p);
  if (!o.contacts.empty()) notes.push_back("static-contacts log: " + o.contacts);
  if (!o.teaching.empty()) notes.push_back("teaching log: " + o.teaching);
  const auto html = std::filesystem::path(o.out) / "evaluate.html";
  evaluation_report(ev, simulated, notes).write(html);
  tpf::AtomicFile json(std::filesystem::path(o.out) / "evaluation.json");
  json.write(evaluation_json(ev));
  json.commit();
  std::printf("%s", evaluation_headline(ev, simulated).c_str());
  if (o.verbose) print_per_joint_table(ev);
  std::printf("evaluate: report %s, every number in %s\n", html.string().c_str(),
              (std::filesystem::path(o.out) / "evaluation.json").string().c_str());
}

}  // namespace

namespace tpf::cli {

void register_evaluate_command(CLI::App& app) {
  auto o = std::make_shared<EvaluateCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "evaluate", "Compare tactile-only, proprioceptive-only and fusion on held-out logs");
  cmd->footer(
      "Compare tactile-only, proprioceptive-only and fusion on held-out logs: Table I (residual "
      "per regime, nominal vs TCN), dead bands, detection latency, force error, teaching"
      "\nExample: tpf evaluate --params arm4.params.json --weights arm4.tcn.json --calibration "
      "cal.csv --excitation ex.csv --contacts contacts.csv --out report");
  add_model_file_options(cmd, o->model, "Nominal model (tpf-params file)");
  cmd->add_option("--weights", o->weights,
                  "Compensator weights (all joints, or <stem>.joint<j>.json per joint)")
      ->check(weights_path());
  cmd->add_option("--calibration", o->calibration,
                  "Contact-free log for the dead-band σ (not a test log, not the training log)")
      ->required()
      ->check(input_file());
  cmd->add_option("--excitation", o->excitation, "Held-out contact-free excitation log(s)")
      ->required()
      ->check(input_file());
  cmd->add_option("--contacts", o->contacts, "Static-contacts log (detection, force error)")
      ->check(input_file());
  cmd->add_option("--teaching", o->teaching, "Teaching log")->check(input_file());
  cmd->add_option("--teaching-scenario", o->teaching_scenario,
                  "Teaching scenario to simulate in closed loop through the estimators")
      ->check(input_file());
  cmd->add_option("--teaching-seed", o->teaching_seed, "Seed of the closed-loop runs")
      ->capture_default_str()
      ->check(non_negative());
  cmd->add_option("--teaching-duration", o->teaching_duration, "Closed-loop run length [s]")
      ->capture_default_str()
      ->check(positive(kMaxSimulatedSeconds));
  cmd->add_option("--out", o->out, "Output folder (evaluate.html, evaluation.json)")->required();
  cmd->add_flag("--quiet", o->quiet, "No progress lines");
  cmd->add_flag("--verbose", o->verbose, "Also Table I per joint (evaluation.json: every number)");
  cmd->callback([o] {
    refuse_colliding_outputs(*o);
    run_evaluate(*o);
  });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
