// `tpf diagnose`: identify the declared model, trace the residual to missing effects, add them,
// refit, and report before and after on held-out data.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "core/common/atomic_file.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "heap_reuse.hpp"
#include "identification_printout.hpp"
#include "offline/diagnose/diagnosis_report.hpp"
#include "offline/diagnose/diagnosis_summary.hpp"
#include "offline/log/read_logs.hpp"
#include "offline/log/torque_sensor.hpp"
#include "offline/report/text_table.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"
#include "read_command_logs.hpp"
#include "robot_joint_count.hpp"
#include "tpf/common/error.hpp"
#include "tpf/model/load_robot.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace {

struct DiagnoseArgs {
  std::vector<std::string> logs;
  std::string robot, report, json, params, identify_out;
  double static_velocity = 1e-4, min_improvement = 0.10;
  bool quiet = false, verbose = false, inertia_prior = true;
  bool no_load_friction = false, friction_from_sensor = false;  ///< of --identify-out's fit
};

/// With --identify-out: identify (with the friction options of `a`) on the samples diagnose then
/// takes over, read and regressed once; prints and writes what `tpf identify` would.
tpf::offline::Diagnosis identify_then_diagnose(const tpf::offline::Log& log,
                                               const tpf::offline::ModelX& model,
                                               const tpf::offline::DiagnoseOptions& options,
                                               const DiagnoseArgs& a) {
  using namespace tpf::offline;
  const auto start = std::chrono::steady_clock::now();
  IdentificationSetup setup = prepare_diagnosis(log, model, options.samples);
  const auto gravity = setup.gravity;  // G(q): the gravity load, the unit checks and diagnose's
  const tpf::BaseParameters base = setup.base;
  const auto regressors = setup.regressors;
  const auto abs_gravity = setup.abs_gravity;
  IdentifyOptions identify_options;
  identify_options.samples = options.samples;
  identify_options.progress = options.progress;
  identify_options.fit_load_friction = !a.no_load_friction;
  identify_options.friction_from_sensor = a.friction_from_sensor;
  identify_options.inertia_prior = a.inertia_prior;
  Identification id = identify(log, model, std::move(setup), identify_options);
  tpf::cli::print_and_save_identification(log, id, options.samples, a.identify_out, start,
                                          tpf::cli::check_log_units(model, id.samples, *gravity),
                                          a.verbose);
  return diagnose(log, model, {std::move(id.samples), base, regressors, abs_gravity, gravity}, id,
                  options);
}

/// The inertia prior's line, when identify's fits, and so diagnose's, needed one.
void print_inertia_prior(const tpf::offline::EffectDiagnosis& d) {
  const auto& prior = d.inertia_prior;
  if (prior.judged_strength > 0 || prior.written_strength > 0)
    std::printf(
        "inertia prior: M(q)'s smallest eigenvalue without it %.4g kg·m² (identify's declared "
        "fit); the fits pulled toward the robot file's inertias with identify's strengths %.3g "
        "(the selection's) and %.3g (the written model's refit on every row): %s\n",
        prior.judged_min_eigenvalue, prior.judged_strength, prior.written_strength,
        prior.choice.c_str());
}

/// Everything: the findings, notes, the inertia prior and the held-out table per joint and regime.
void print_in_full(const tpf::offline::Diagnosis& d) {
  using namespace tpf::offline;
  for (const auto& f : d.findings)
    std::printf("%s\n", f.c_str());
  for (const auto& n : d.notes)
    std::printf("note: %s\n", n.c_str());
  print_inertia_prior(d);
  const char* names[4] = {"static", "static-to-kinetic", "moving", "all"};
  std::printf(
      "held-out RMSE [%s] before -> after: the selection's linear fit (friction held at "
      "rest) | the written model (--params: friction curve, run-time effects only)\n",
      d.samples.units.name());
  const Regime regimes[4] = {Regime::Static, Regime::StaticToKinetic, Regime::Moving,
                             Regime::Invalid};
  for (int j = 0; j < d.joints(); ++j)
    for (int r = 0; r < 4; ++r) {
      const auto& wb = d.written_before[j];
      const auto& wa = d.written_after[j];
      // Fitted in N·m; printed in the log's unit (mA for a log of currents).
      const auto in_log_unit = [&](double tau) { return d.samples.units.to_effort(j, tau); };
      const double b = in_log_unit(r < 3 ? wb[regimes[r]].rmse : wb.valid.rmse);
      const double w = in_log_unit(r < 3 ? wa[regimes[r]].rmse : wa.valid.rmse);
      const double before = in_log_unit(d.before[j][r].rmse());
      const double after = in_log_unit(d.after[j][r].rmse());
      std::printf("  joint %d %-18s %10.3f -> %10.3f  (%+.1f %%) | %10.3f -> %10.3f  (%+.1f %%)\n",
                  j + 1, names[r], before, after, percent_change(before, after), b, w,
                  percent_change(b, w));
    }
}

/// The verdict per effect and, per joint, the written model's held-out RMSE before and after.
void print_brief(const tpf::offline::Diagnosis& d, const tpf::offline::DiagnoseOptions& o) {
  using namespace tpf::offline;
  const Table verdict = diagnosis_summary_table(d, o);
  if (verdict.rows.empty())  // nothing to show: the findings say why
    for (const auto& f : d.findings)
      std::printf("%s\n", f.c_str());
  else
    std::printf("%s", table_text(verdict).c_str());
  print_inertia_prior(d);
  std::printf("held-out RMSE [%s] of the written model (--params), declared -> with the effects:\n",
              d.samples.units.name());
  for (int j = 0; j < d.joints(); ++j) {
    std::printf("  joint %d", j + 1);
    for (const Regime r : {Regime::Static, Regime::StaticToKinetic, Regime::Moving}) {
      const double b = d.samples.units.to_effort(j, d.written_before[j][r].rmse);
      const double w = d.samples.units.to_effort(j, d.written_after[j][r].rmse);
      std::printf("  %s %.4g -> %.4g (%+.0f %%)", std::string(regime_name(r)).c_str(), b, w,
                  percent_change(b, w));
    }
    std::printf("\n");
  }
  std::printf("(--verbose: the findings in full, notes, every regime of both fits)\n");
}

void run(const tpf::offline::Log& log, const DiagnoseArgs& a) {
  using namespace tpf::offline;
  DiagnoseOptions options;
  options.samples.regimes.static_velocity = a.static_velocity;
  options.min_improvement = a.min_improvement;
  options.inertia_prior = a.inertia_prior;
  if (!a.quiet)
    options.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  const ModelX model = tpf::load_robot<double, Eigen::Dynamic>(a.robot);
  const Diagnosis d = a.identify_out.empty() ? diagnose(log, model, options)
                                             : identify_then_diagnose(log, model, options, a);
  if (d.samples.simulated) std::printf("SIMULATED log (digital twin)\n");
  if (a.verbose)
    print_in_full(d);
  else
    print_brief(d, options);
  if (!a.report.empty()) {
    write_diagnosis_report(d, a.report, options);
    std::printf("wrote %s\n", a.report.c_str());
  }
  if (!a.json.empty()) {
    tpf::AtomicFile out(a.json);  // complete or absent, never half-written
    out.write(diagnosis_json(d) + "\n");
    out.commit();
    std::printf("wrote %s\n", a.json.c_str());
  }
  if (!a.params.empty()) {
    tpf::save_nominal_model(a.params, d.nominal, log.source, "");
    std::printf("wrote %s%s\n", a.params.c_str(),
                d.refitted ? ": the written model refitted on every sample, the held-out ones "
                             "included (the tables above are of its fit without them)"
                           : "");
  }
}

}  // namespace

namespace tpf::cli {

/// Adds `tpf diagnose` to the app.
void register_diagnose_command(CLI::App& app) {
  auto a = std::make_shared<DiagnoseArgs>();
  CLI::App* cmd = app.add_subcommand(
      "diagnose", "Find which physical effect the nominal model misses, add it, check it held out");
  cmd->footer(
      "Identify the declared model, find which candidate physical effect (load-dependent friction, "
      "ripple, payload, temperature, spring, delay, coupling) explains the residual on held-out "
      "data, add it, refit and report before/after; --params gets the model refitted on every "
      "sample"
      "\nExample: tpf diagnose --log ex.csv --robot data/arm4.robot.json --report diagnose.html "
      "--params arm4.params.json");
  cmd->add_option("--log", a->logs,
                  "Log(s) (tpf CSV or .csv.gz); several are read as one, each file its own segment")
      ->required()
      ->check(input_file());
  cmd->add_option("--robot", a->robot, "Robot file")->required()->check(input_file());
  cmd->add_option("--report", a->report, "HTML report to write");
  cmd->add_option("--json", a->json, "The same numbers as JSON");
  cmd->add_option("--params", a->params, "Parameter file of the extended model (tpf-params)");
  CLI::Option* identify_out = cmd->add_option(
      "--identify-out", a->identify_out,
      "Also identify the declared model first, as `tpf identify --out FILE` with this "
      "--static-velocity (and --no-load-friction, --friction-from-sensor) would: the same "
      "file and table, printed before the diagnosis; the log is read and its regressors "
      "computed once for both");
  cmd->add_flag("--no-load-friction", a->no_load_friction,
                "With --identify-out: its fit keeps α_c = α_v = 0, as tpf identify's")
      ->needs(identify_out);
  cmd->add_flag("--friction-from-sensor", a->friction_from_sensor,
                "With --identify-out: its friction fitted against each joint's torque sensor, "
                "as tpf identify's (see tpf identify --help)")
      ->needs(identify_out);
  cmd->add_flag("--inertia-prior,!--no-inertia-prior", a->inertia_prior,
                "On by default: where the declared model's M(q) is not positive definite, "
                "identify's fit is pulled toward the robot file's inertias, and every fit of the "
                "diagnosis with identify's strengths. --no-inertia-prior: every fit plain");
  cmd->add_option("--static-velocity", a->static_velocity, "Static threshold |q̇| [rad/s]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--min-improvement", a->min_improvement,
                  "Share of the held-out residual sum of squares an effect must remove")
      ->capture_default_str()
      ->check(in_half_open(0.0, 1.0));
  cmd->add_flag("--quiet", a->quiet, "No progress lines");
  cmd->add_flag("--verbose", a->verbose,
                "Print the findings in full, the notes and the held-out table of both fits per "
                "joint and regime (by default: the verdict per effect and the written model's "
                "held-out error)");
  cmd->callback([a] {
    refuse_overwriting_inputs("diagnose",
                              joined(each_of("--log", a->logs), {{"--robot", a->robot}}),
                              {{"--report", a->report},
                               {"--json", a->json},
                               {"--params", a->params},
                               {"--identify-out", a->identify_out}});
    reuse_freed_memory();
    const offline::Log log = read_command_logs(a->logs);
    require_log_joint_count(log.joint_count(), log.source, a->robot);
    run(log, *a);
  });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
