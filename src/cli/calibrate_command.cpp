// `tpf calibrate`: the estimator parameter file of an arm from a contact-free calibration log,
// once, offline; the run-time loop (tpf_arm_loop --estimator) loads it at start-up.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>

#include "commands.hpp"
#include "compensator_gate_printout.hpp"
#include "model_file_options.hpp"
#include "offline/calibrate/estimator_calibration.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "offline/log/read_log.hpp"
#include "option_validators.hpp"
#include "output_collisions.hpp"
#include "read_command_logs.hpp"
#include "tpf/estimation/estimator_parameter_file.hpp"
#include "tpf/estimation/load_estimator.hpp"
#include "tpf/model/effort_unit.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

namespace {

struct CalibrateCommandOptions {
  std::string log, weights, out;
  tpf::cli::ModelFiles model;
  double pad_gain_kpa_per_n = 1.5;
};

std::string joint_values(const Eigen::VectorXd& v) {
  std::string s;
  char item[32];
  for (int j = 0; j < v.size(); ++j) {
    std::snprintf(item, sizeof item, "%s%.3g", j == 0 ? "" : " ", v[j]);
    s += item;
  }
  return s;
}

void run_calibrate(const CalibrateCommandOptions& o) {
  using namespace tpf::offline;
  const ReplaySetup setup = tpf::cli::load_model_setup(o.model, o.weights);
  const int joints = setup.nominal.model.joint_count();
  const Log log = tpf::cli::read_replayed_log(o.log, false);
  const ReplayParameters p = calibrate_estimator(setup, log, o.pad_gain_kpa_per_n);

  const auto origin = log.meta.get("source");
  const bool simulated = origin && origin->find("simulated") != std::string::npos;
  std::string source = o.log + (simulated ? " (SIMULATED log)" : "") + ", nominal model " +
                       o.model.params + ", compensator " + (o.weights.empty() ? "none" : o.weights);
  tpf::save_estimator_parameters(o.out, p, source);
  // Calibrated in N·m; printed in the log's unit (mA for a log of currents).
  const tpf::DriveUnits units =
      tpf::drive_units(setup.nominal.model, tpf::effort_unit_of_column(log.effort_prefix()));
  const std::string unit = units.name();
  const auto in_log_unit = [&](const Eigen::VectorXd& tau) {
    return Eigen::VectorXd(units.to_effort(Eigen::MatrixXd(tau.transpose())).transpose());
  };
  std::printf("calibrate: %s%s, %d joints, %s, %s\n", o.log.c_str(),
              simulated ? " (SIMULATED)" : "", joints,
              tpf::cli::describe_pads(
                  setup.pads.size(),
                  tpf::cli::pad_layout_file(o.model, tpf::load_robot_description(o.model.robot)))
                  .c_str(),
              describe(setup.weights).c_str());
  tpf::cli::print_compensated_joints("calibrate", setup.weights, joints,
                                     p.compensator_min_held_out_gain);
  std::printf("  static dead band [%s]: %s\n", unit.c_str(),
              joint_values(in_log_unit(p.static_dead_band)).c_str());
  std::printf("  transition sigma, nominal [%s]: %s\n", unit.c_str(),
              joint_values(in_log_unit(p.nominal_sigma)).c_str());
  std::printf("  transition sigma, fused [%s]: %s\n", unit.c_str(),
              joint_values(in_log_unit(p.fused_sigma)).c_str());
  if (setup.pads.empty())
    std::printf("  pad contact on/off [kPa]: no skin\n");
  else
    std::printf("  pad contact on/off [kPa]: %.3g / %.3g\n", p.skin.detector.on_level_kpa,
                p.skin.detector.off_level_kpa);
  std::printf("  compensator domain, |joint speed| up to [rad/s]: %s\n",
              joint_values(p.compensator_speed_limit).c_str());
  std::printf("  compensator domain, |joint acceleration| up to [rad/s^2]: %s\n",
              joint_values(p.compensator_acceleration_limit).c_str());
  std::printf("  torque-only contact alarm: %d cycles in a row\n", p.torque_alarm_samples);
  std::printf("calibrate: wrote %s\n", o.out.c_str());
}

}  // namespace

namespace tpf::cli {

void register_calibrate_command(CLI::App& app) {
  auto o = std::make_shared<CalibrateCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "Calibrate the run-time estimator's parameters on a contact-free log");
  cmd->footer(
      "The log: the arm at rest and moving every joint, nothing touching it. Finds the sensor "
      "noise (-> dead bands, pad contact levels), the compensator's domain (top speed and "
      "acceleration per joint), the transition sigma of the nominal and compensated residuals "
      "and the shortest torque-only alarm persistence that raises no alarm on this log. Writes "
      "the estimator parameter file (tpf-estimator) tpf_arm_loop --estimator and tpf estimate "
      "load. Run it again when the arm, its nominal model or its compensator changes.\n"
      "Example: tpf calibrate --log free.csv --params arm4.params.json --weights arm4.tcn.json "
      "--out arm4.estimator.json");
  cmd->add_option("--log", o->log,
                  "Contact-free calibration log (tpf CSV, effort i<j> in mA or tau<j> in N*m)")
      ->required()
      ->check(input_file());
  add_model_file_options(cmd, o->model, "Nominal model (tpf-params file)");
  cmd->add_option("--weights", o->weights,
                  "Compensator weights the loop will run (all joints, or <stem>.joint<j>.json per "
                  "joint); without: the fused dead band is calibrated with no compensator")
      ->check(weights_path());
  cmd->add_option("--pad-gain", o->pad_gain_kpa_per_n,
                  "Pad pressure per normal force on the 25 cm^2 reference pad [kPa/N]")
      ->capture_default_str()
      ->check(positive());
  cmd->add_option("--out", o->out, "Estimator parameter file to write, e.g. arm4.estimator.json")
      ->required();
  cmd->callback([o] {
    refuse_overwriting_inputs("calibrate",
                              joined(joined({{"--log", o->log}}, model_inputs(o->model)),
                                     weight_files("--weights", o->weights)),
                              {{"--out", o->out}});
    run_calibrate(*o);
  });
}

}  // namespace tpf::cli

TPF_UNOPTIMISED_WHEN_SANITIZED_END
