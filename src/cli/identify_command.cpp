// `tpf identify`: identify the arm's nominal model from a log and write a parameter file.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "heap_reuse.hpp"
#include "identification_printout.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/identify/identification_setup.hpp"
#include "offline/identify/identify.hpp"
#include "offline/log/read_logs.hpp"
#include "offline/log/torque_sensor.hpp"
#include "offline/samples/joint_samples.hpp"
#include "offline/samples/sample_unit_check.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"
#include "read_command_logs.hpp"
#include "robot_joint_count.hpp"
#include "tpf/common/error.hpp"
#include "tpf/model/load_robot.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace {

struct IdentifyArgs {
  std::vector<std::string> logs;
  std::string robot, out;
  double static_velocity = 1e-4;
  bool no_load_friction = false, quiet = false, verbose = false, friction_from_sensor = false,
       inertia_prior = true;
};

void run(const tpf::offline::Log& log, const IdentifyArgs& a) {
  using namespace tpf::offline;
  using tpf::cli::print_and_save_identification;
  const auto start = std::chrono::steady_clock::now();
  IdentifyOptions options;
  options.samples.regimes.static_velocity = a.static_velocity;
  options.fit_load_friction = !a.no_load_friction;
  options.friction_from_sensor = a.friction_from_sensor;
  options.inertia_prior = a.inertia_prior;
  if (!a.quiet)
    options.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  const ModelX model = tpf::load_robot<double, Eigen::Dynamic>(a.robot);
  IdentificationSetup setup = prepare_identification(log, model, options.samples);
  // G(q) of the samples once: the gravity load of the friction fit and the unit checks read it.
  const Eigen::MatrixXd gravity = gravity_torque(model, setup.samples);
  setup.abs_gravity = std::make_shared<const Eigen::MatrixXd>(gravity_load(gravity, setup.samples));
  const Identification id = identify(log, model, std::move(setup), options);
  print_and_save_identification(log, id, options.samples, a.out, start,
                                tpf::cli::check_log_units(model, id.samples, gravity), a.verbose);
}

}  // namespace

namespace tpf::cli {

/// Adds `tpf identify` to the app.
void register_identify_command(CLI::App& app) {
  auto a = std::make_shared<IdentifyArgs>();
  CLI::App* cmd = app.add_subcommand(
      "identify", "Identify the nominal model (rigid body, armature, friction) from a log");
  cmd->footer(
      "Identify rigid-body base parameters (with armature) and Stribeck + load-dependent friction "
      "from a log by weighted least squares and Ceres; validate on held-out data (the last file "
      "of several, else every 4th 5 s block), then write the model refitted on every sample"
      "\nExample: tpf identify --log ex.csv --robot data/arm4.robot.json --out arm4.params.json");
  cmd->add_option("--log", a->logs,
                  "Log(s) (tpf CSV or .csv.gz; i<j> in mA or tau<j> in N·m); several are read as "
                  "one, each file its own segment")
      ->required()
      ->check(input_file());
  cmd->add_option("--robot", a->robot, "Robot file, e.g. data/arm4.robot.json")
      ->required()
      ->check(input_file());
  cmd->add_option("--out", a->out, "Parameter file to write (tpf-params JSON)")->required();
  cmd->add_option("--static-velocity", a->static_velocity, "Static threshold |q̇| [rad/s]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_flag("--no-load-friction", a->no_load_friction, "Keep α_c = α_v = 0");
  cmd->add_flag("--friction-from-sensor", a->friction_from_sensor,
                "Fit each joint's friction against its joint torque sensor (tau_sensor<j>, "
                "where it varies): effort - K*(tau_sensor + Ia*q''), the drive loss behind the "
                "gear, instead of effort - rigid-body prediction");
  cmd->add_flag("--inertia-prior,!--no-inertia-prior", a->inertia_prior,
                "On by default: where the fitted mass matrix M(q) is not positive definite (a log "
                "that does not excite every inertia), the rigid body is pulled toward the robot "
                "file's inertias with the relative prior strength of lowest held-out error among "
                "those (0, 1e-4 ... 100, and the smallest that lifts it) that lift M(q)'s smallest "
                "eigenvalue, at 200 poses, to a tenth of the robot file's own (the strengths tried "
                "are printed, and kept in the file's fit). --no-inertia-prior: the plain "
                "least-squares fit, whatever M(q)");
  cmd->add_flag("--quiet", a->quiet, "No progress lines");
  cmd->add_flag("--verbose", a->verbose,
                "Every note and the inertia prior's strengths tried (default: the first lines; "
                "the parameter file's \"fit\" keeps them all)");
  cmd->callback([a] {
    refuse_overwriting_inputs("identify",
                              joined(each_of("--log", a->logs), {{"--robot", a->robot}}),
                              {{"--out", a->out}});
    reuse_freed_memory();
    const offline::Log log = read_command_logs(a->logs);
    require_log_joint_count(log.joint_count(), log.source, a->robot);
    run(log, *a);
  });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
