// tpf — tactile–proprioceptive fusion: the command-line tools.
#include <exception>
#include <iostream>

#include "commands.hpp"
#include "core/common/atomic_file.hpp"
#include "core/common/unoptimised_when_sanitized.hpp"
#include "tpf/common/error.hpp"

TPF_UNOPTIMISED_WHEN_SANITIZED_BEGIN

int main(int argc, char** argv) {
  CLI::App app{
      "tpf: external torque and contact wrench estimation for geared robot arms.\n"
      "Simulate the arm's digital twin, identify a model from a log, diagnose what it misses,\n"
      "train the friction compensator and evaluate the estimators. Logs: docs/log-format.md."};
  // Interrupted or killed: no hidden temporary is left beside the files being written.
  tpf::remove_temporaries_on_termination();
  app.require_subcommand(1);
  app.set_version_flag("--version", "tpf 0.1.0");
  tpf::cli::register_info_command(app);
  tpf::cli::register_demo_command(app);
  tpf::cli::register_simulate_command(app);
  tpf::cli::register_identify_command(app);
  tpf::cli::register_diagnose_command(app);
  tpf::cli::register_train_command(app);
  tpf::cli::register_evaluate_command(app);
  tpf::cli::register_calibrate_command(app);
  tpf::cli::register_estimate_command(app);
  tpf::cli::register_import_command(app);
  tpf::cli::register_validate_command(app);
  tpf::cli::register_upgrade_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const tpf::Error& e) {
    std::cerr << "tpf: error: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "tpf: unexpected error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}

TPF_UNOPTIMISED_WHEN_SANITIZED_END
