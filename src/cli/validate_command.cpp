// `tpf validate`: a saved parameter file applied to other logs (held out by log): effort RMSE per
// joint and regime in the log's unit, and current-based joint torque against the torque sensor.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "compensator_gate_printout.hpp"
#include "core/common/atomic_file.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/log/read_logs.hpp"
#include "offline/samples/joint_samples.hpp"
#include "offline/validate/validation.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"
#include "robot_joint_count.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/estimation/nominal_model.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace {

struct ValidateArgs {
  std::string params, robot, json, weights, estimator;
  std::vector<std::string> logs;
  double static_velocity = 1e-4;
  bool verbose = false;
};

/// validation_text without its sensor comparison per regime and per file (from "the same per
/// regime" on): the default printout; --verbose prints it whole.
std::string brief_validation_text(const std::string& text) {
  const std::size_t cut = text.find("the same per regime");
  if (cut == std::string::npos) return text;
  return text.substr(0, cut) +
         "(--verbose: the sensor comparison per regime and per file; --json: every number)\n";
}

void run_validate(const tpf::offline::Log& log, const ValidateArgs& a) {
  using namespace tpf::offline;
  const tpf::NominalModelX nominal = tpf::load_nominal_model(a.params, a.robot);
  const int joints = nominal.model.joint_count();
  SampleOptions options;
  options.regimes.static_velocity = a.static_velocity;
  options.all_held_out = true;  // fitted on other logs: every row of this one is held out
  const JointSamples samples = extract_joint_samples(log, nominal.model.torque_constant, options);
  std::vector<std::string> notes;
  // One column per estimate; the compensator (--weights) becomes one more here.
  std::vector<EffortEstimate> estimates{nominal_estimate(nominal, samples, notes)};
  if (!a.weights.empty()) {
    tpf::EstimatorSetup<Eigen::Dynamic> setup;
    setup.nominal = nominal;
    if (a.estimator.empty())
      setup.parameters.resize(joints);
    else
      setup.parameters = tpf::load_estimator_parameters(a.estimator, joints);
    setup.weights = tpf::find_compensator_weights(a.weights, joints);
    tpf::cli::print_compensated_joints("validate", setup.weights, joints,
                                       setup.parameters.compensator_min_held_out_gain);
    estimates.push_back(compensated_estimate(setup, log, estimates.front()));
  }
  Validation v = score_estimates(log, samples, estimates);
  v.notes = notes;
  std::printf("validate: %s on %s (%s)\n", a.params.c_str(), log.source.c_str(),
              samples.simulated ? "SIMULATED" : "held out by log");
  std::printf("  %s; samples: %s\n", log.quality.summary(log.columns).c_str(),
              tpf::offline::skipped_samples_text(samples).c_str());
  bool sensor = false;
  for (const SensorScore& score : v.sensor)
    sensor = sensor || score.samples > 0;
  for (const std::string& n : notes)  // the armature matters only against a sensor
    if (sensor || n.find("armature") == std::string::npos) std::printf("note: %s\n", n.c_str());
  const std::string text = validation_text(v);
  std::printf("%s", (a.verbose ? text : brief_validation_text(text)).c_str());
  if (!a.json.empty()) {
    tpf::write_file_atomically(a.json, validation_json(v) + "\n");
    std::printf("wrote %s\n", a.json.c_str());
  }
}

}  // namespace

namespace tpf::cli {

void register_validate_command(CLI::App& app) {
  auto a = std::make_shared<ValidateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "validate", "Score a saved parameter file on other logs (and against a torque sensor)");
  cmd->footer(
      "Apply a saved parameter file to other logs (held out by log: none of them was fitted on) "
      "and print the effort RMSE per joint and regime in the log's unit, and, where the log has "
      "a joint torque sensor (tau_sensor<j>), the RMSE of the current-based joint torque "
      "Kt*i - friction - armature*q'' against it (Kt only and the maker's tau_maker<j> beside)"
      "\nExample: tpf validate --params arm4.params.json --robot data/arm4.robot.json --log "
      "held-out.csv");
  cmd->add_option("--params", a->params, "Parameter file (tpf-params) from identify/diagnose")
      ->required()
      ->check(input_file());
  cmd->add_option("--robot", a->robot, "Robot file the parameters were identified for")
      ->required()
      ->check(input_file());
  cmd->add_option("--log", a->logs,
                  "Held-out log(s) (.csv or .csv.gz); several are scored "
                  "together, each its own segment")
      ->required()
      ->check(input_file());
  cmd->add_option("--weights", a->weights,
                  "Friction compensator (tpf train: one file, or <stem>.joint<j>.json per joint): "
                  "adds the column 'with the compensator'")
      ->check(weights_path());
  cmd->add_option("--estimator", a->estimator,
                  "Estimator parameter file (tpf calibrate) the compensator runs with (default: "
                  "the defaults; only the static-friction tracker and the q'' filter matter here)")
      ->check(input_file());
  cmd->add_option("--json", a->json, "The same numbers as JSON");
  cmd->add_flag("--verbose", a->verbose,
                "Also the torque-sensor comparison per regime and per file");
  cmd->add_option("--static-velocity", a->static_velocity, "Static threshold |q̇| [rad/s]")
      ->capture_default_str()
      ->check(positive());
  cmd->callback([a] {
    refuse_overwriting_inputs(
        "validate",
        joined(joined({{"--params", a->params}, {"--robot", a->robot}}, each_of("--log", a->logs)),
               joined(weight_files("--weights", a->weights), {{"--estimator", a->estimator}})),
        {{"--json", a->json}});
    std::vector<std::string> notes;
    const offline::Log log = offline::read_logs(a->logs, &notes);
    for (const std::string& n : notes)
      std::printf("note: %s\n", n.c_str());
    require_log_joint_count(log.joint_count(), log.source, a->robot);
    run_validate(log, *a);
  });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
